# Sourced by scripts/test.sh and scripts/fuzz.sh: the compiler flags of the
# instrumented builds (ASan + UBSan and TSan in test.sh, the libFuzzer targets
# in fuzz.sh), passed as CMAKE_CXX_FLAGS_RELWITHDEBINFO. -O1 and line tables
# only (-g1: file and line in every report, no variable info; the -O1 that
# libFuzzer's documentation builds with). Against -O2 -g on the 2-core
# machine: the ASan + UBSan build 306 s -> 163 s with its tests as fast
# (62 s), the TSan build 177 s -> 133 s.
# shellcheck shell=bash disable=SC2034
instrumented_flags="-O1 -g1 -DNDEBUG"
