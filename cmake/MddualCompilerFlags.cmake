# Warnings and sanitizers for mddual's own targets, applied through an
# interface target so that consumers of the installed package are not affected.
add_library(mddual_build_flags INTERFACE)
target_compile_options(mddual_build_flags INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion
  -Wnon-virtual-dtor -Wold-style-cast -Wcast-align -Woverloaded-virtual)
if(MDDUAL_WARNINGS_AS_ERRORS)
  target_compile_options(mddual_build_flags INTERFACE -Werror)
endif()

if(MDDUAL_SANITIZE)
  string(REPLACE ";" "," _mddual_san "${MDDUAL_SANITIZE}")
  if(NOT _mddual_san MATCHES "^(address|undefined|thread|address,undefined|undefined,address)$")
    message(FATAL_ERROR "MDDUAL_SANITIZE='${MDDUAL_SANITIZE}': use 'address,undefined' or 'thread'")
  endif()
  message(STATUS "mddual: building with -fsanitize=${_mddual_san}")
  target_compile_options(mddual_build_flags INTERFACE
    -fsanitize=${_mddual_san} -fno-omit-frame-pointer -fno-sanitize-recover=all)
  target_link_options(mddual_build_flags INTERFACE -fsanitize=${_mddual_san})
endif()

# Fuzzing (fuzz/): every mddual target gets libFuzzer's coverage
# instrumentation and ASan + UBSan; the fuzz executables add the libFuzzer
# driver (-fsanitize=fuzzer).
if(MDDUAL_BUILD_FUZZERS)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "MDDUAL_BUILD_FUZZERS needs Clang (CXX=clang++; Debian packages clang and libclang-rt-14-dev)")
  endif()
  if(MDDUAL_SANITIZE)
    message(FATAL_ERROR "MDDUAL_BUILD_FUZZERS brings its own sanitizers: leave MDDUAL_SANITIZE empty")
  endif()
  target_compile_options(mddual_build_flags INTERFACE
    -fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all)
  target_link_options(mddual_build_flags INTERFACE -fsanitize=address,undefined)
endif()

# Use as: target_link_libraries(tgt PRIVATE $<BUILD_INTERFACE:mddual_build_flags>)
# (BUILD_INTERFACE keeps the flags out of the exported package).
