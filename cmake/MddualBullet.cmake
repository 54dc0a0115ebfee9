# Bullet's double-precision ("-float64") build, as Debian's libbullet-dev ships
# it. Bullet's own CMake config uses prefix-relative paths, so the headers and
# libraries are found directly. Sets MDDUAL_BULLET_FOUND, MDDUAL_BULLET_INCLUDE_DIR,
# MDDUAL_BULLET_COLLISION_LIB and MDDUAL_BULLET_LINEARMATH_LIB. Users of the
# headers define BT_USE_DOUBLE_PRECISION. (No REQUIRED on find_path/find_library:
# that needs CMake 3.18, we require 3.16.)
find_path(MDDUAL_BULLET_INCLUDE_DIR btBulletCollisionCommon.h PATH_SUFFIXES bullet)
find_library(MDDUAL_BULLET_COLLISION_LIB BulletCollision-float64)
find_library(MDDUAL_BULLET_LINEARMATH_LIB LinearMath-float64)
if(MDDUAL_BULLET_INCLUDE_DIR AND MDDUAL_BULLET_COLLISION_LIB AND MDDUAL_BULLET_LINEARMATH_LIB)
  set(MDDUAL_BULLET_FOUND TRUE)
else()
  set(MDDUAL_BULLET_FOUND FALSE)
endif()
