#!/usr/bin/env bash
# Installs every Debian 12 package FiberPLI needs to build, test and run (docs/architecture.md §5).
# Idempotent and non-interactive. Run as root (or with sudo available).
set -euo pipefail

packages=(
  cmake g++ make pkg-config paraview paraview-dev python3-paraview
  qtbase5-dev qttools5-dev libqt5svg5-dev libqt5opengl5-dev qtxmlpatterns5-dev-tools
  libopenmpi-dev openmpi-bin libhdf5-openmpi-dev libnetcdf-dev
  libboost-dev libexpat1-dev libavcodec-dev libavformat-dev libavutil-dev libswscale-dev
  libfreetype-dev libgdal-dev libgl2ps-dev libglew-dev libjpeg-dev liblz4-dev liblzma-dev
  libxml2-dev libgl-dev libpng-dev python3-dev libtheora-dev libtiff-dev libx11-dev libxt-dev
  libxcursor-dev zlib1g-dev libdouble-conversion-dev libutfcpp-dev python3-mpi4py
  libgtest-dev xvfb xauth python3-numpy python3-scipy clang-format
)

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  sudo_cmd=(sudo)
fi

export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -q
"${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${packages[@]}"
