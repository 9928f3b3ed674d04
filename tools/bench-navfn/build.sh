#!/usr/bin/env bash
# tools/bench-navfn/build.sh NAVIGATION_CHECKOUT OUT_DIR [CXXFLAGS...]
# Builds ROS navfn's planner core (navfn/src/navfn.cpp and navfn/include/navfn/navfn.h of a ros-planning/navigation
# source checkout, unchanged) with navfn_driver.cpp into OUT_DIR/navfn-driver. navfn's sources are copied into OUT_DIR
# (a temporary folder), never into this repository; ros/console.h is replaced by a stub whose logging macros do
# nothing. Default flags: -O2 (ROS's RelWithDebInfo/Release builds use -O2/-O3; pass e.g. -O3 -march=native to compare).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
navigation=${1:?usage: build.sh NAVIGATION_CHECKOUT OUT_DIR [CXXFLAGS...]}
out=${2:?usage: build.sh NAVIGATION_CHECKOUT OUT_DIR [CXXFLAGS...]}
shift 2
flags=("$@")
[ ${#flags[@]} -gt 0 ] || flags=(-O2)
for f in navfn/src/navfn.cpp navfn/include/navfn/navfn.h; do
    [ -f "$navigation/$f" ] || { echo "build.sh: $navigation/$f not found (a ros-planning/navigation checkout?)" >&2; exit 2; }
done
mkdir -p "$out/src" "$out/include/navfn" "$out/include/ros"
cp "$navigation/navfn/src/navfn.cpp" "$out/src/"
cp "$navigation/navfn/include/navfn/navfn.h" "$out/include/navfn/"
cat > "$out/include/ros/console.h" <<'STUB'
// stub of ROS logging for a build of navfn.cpp outside ROS: the macros do nothing; <algorithm> as the real header
// brings it in (navfn.cpp uses std::max and std::min without including it)
#pragma once
#include <algorithm>
#define ROS_DEBUG(...) ((void)0)
#define ROS_INFO(...) ((void)0)
#define ROS_WARN(...) ((void)0)
#define ROS_ERROR(...) ((void)0)
STUB
g++ -std=c++14 "${flags[@]}" -I"$out/include" -o "$out/navfn-driver" "$here/navfn_driver.cpp" "$out/src/navfn.cpp"
echo "$out/navfn-driver"
