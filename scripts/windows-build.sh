#!/usr/bin/env bash
# Builds the Windows program (x86_64-pc-windows-gnu, linked by MinGW-w64) on Linux, and
# beside it the stand-in bcryptprimitives.dll that Wine 8.0 lacks (Rust's std imports its
# ProcessPrng; see scripts/wine/bcryptprimitives.c). Prints the .exe's path last.
#
# Uses Debian's rustc-web toolchain with -Zbuild-std, as scripts/check-targets.sh does;
# missing packages are installed.
set -euo pipefail
cd "$(dirname "$0")/.."

. scripts/need-packages.sh
need_packages rustc-web cargo-web rust-web-src lld-22 gcc-mingw-w64-x86-64

target=x86_64-pc-windows-gnu
out="$PWD/target/windows"
env PATH=/usr/bin:/bin RUSTC=/usr/bin/rustc RUSTC_BOOTSTRAP=1 CARGO_TARGET_DIR="$out" \
  CARGO_TARGET_X86_64_PC_WINDOWS_GNU_LINKER=x86_64-w64-mingw32-gcc \
  /usr/bin/cargo build -Zbuild-std --release --target "$target" --bin shadowmap >&2
dir="$out/$target/release"
x86_64-w64-mingw32-gcc -O2 -shared -o "$dir/bcryptprimitives.dll" \
  scripts/wine/bcryptprimitives.c scripts/wine/bcryptprimitives.def -ladvapi32
echo "$dir/shadowmap.exe"
