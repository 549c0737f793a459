#!/usr/bin/env bash
# Installs the Debian 12 packages indentsim needs, and only those that are missing.
# Idempotent: when everything is present it changes nothing (no apt-get update either).
# Uses sudo only when not running as root.
set -euo pipefail

packages=(cmake g++ ccache libdeal.ii-dev libyaml-cpp-dev libceres-dev libgtest-dev googletest
          python3 python3-numpy python3-matplotlib openmpi-bin libopenblas0-openmp)

missing=()
for package in "${packages[@]}"; do
  status="$(dpkg-query -W -f='${Status}' "$package" 2>/dev/null || true)"
  if [[ "$status" != "install ok installed" ]]; then
    missing+=("$package")
  fi
done

if [[ ${#missing[@]} -eq 0 ]]; then
  echo "install_dependencies: all ${#packages[@]} required Debian packages are installed"
  exit 0
fi

echo "install_dependencies: missing Debian packages: ${missing[*]}"
if ! command -v apt-get > /dev/null 2>&1; then
  echo "install_dependencies: apt-get not found; install these packages by hand" >&2
  exit 1
fi

sudo_cmd=()
if [[ "$(id -u)" -ne 0 ]]; then
  if command -v sudo > /dev/null 2>&1; then
    sudo_cmd=(sudo)
  else
    echo "install_dependencies: not root and sudo not available; install as root:" >&2
    echo "  apt-get install ${missing[*]}" >&2
    exit 1
  fi
fi

echo "install_dependencies: running ${sudo_cmd[*]:+${sudo_cmd[*]} }apt-get update"
"${sudo_cmd[@]}" apt-get update
echo "install_dependencies: running ${sudo_cmd[*]:+${sudo_cmd[*]} }apt-get install -y --no-install-recommends ${missing[*]}"
"${sudo_cmd[@]}" env DEBIAN_FRONTEND=noninteractive \
  apt-get install -y --no-install-recommends "${missing[@]}"
echo "install_dependencies: done"
