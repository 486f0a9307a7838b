#!/usr/bin/env bash
# Neovim's built-in LSP client, headless, opens a xacro file and prints the diagnostics urdfcheck's server sends.
#   tools/nvim_check.sh [FILE]   (default: the macro file of examples/broken/xacro_macro; expects "I004 31")
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
file="${1:-$here/../examples/broken/xacro_macro/urdf/macros/wheel.xacro}"
out="$(mktemp)"
URDFCHECK_NVIM_FILE="$(realpath "$file")" URDFCHECK_NVIM_OUT="$out" URDFCHECK_PYTHON="${PYTHON:-python3}" \
  timeout 180 nvim --headless --clean -u NONE -c "luafile $here/nvim_diagnostics.lua" >/dev/null 2>&1 || true
cat "$out"
rm -f "$out"
