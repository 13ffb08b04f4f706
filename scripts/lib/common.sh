# Shared by scripts/demo and scripts/test: install missing Debian packages, configure, build.
# Sourced, not run. Every function is idempotent, so a second run only rebuilds what changed.

GF_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"

# Debian packages the build, the tests and the demo need.
GF_PACKAGES=(
  build-essential cmake ninja-build pkg-config git
  ccache                      # compiles taken from the cache on a rebuild (cmake/buildSpeed.cmake)
  libbullet-dev libbullet-extras-dev libeigen3-dev libassimp-dev
  libosmesa6-dev libimgui-dev libstb-dev libdeflate-dev zlib1g-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libboost-dev libturbojpeg0-dev  # the browser view (--serve): HTTP front (Beast, Asio), JPEG frames
  libcpp-httplib-dev          # the serve tests' HTTP client
  libcli11-dev libtomlplusplus-dev nlohmann-json3-dev
  ffmpeg
  parallel
  tesseract-ocr               # OCR of the charts' axis units (ctest ChartOcr.*)
  python3 python3-jsonschema  # examples/device-udp/client.py, the scene schema's test
  python3-dev pybind11-dev python3-numpy python3-pytest  # the Python module (app/python/), its tests
  mkdocs                      # the manual (docs/), built with --strict by ctest Docs.*
  chromium                    # headless, for the browser tests (tests/browser/, ctest Browser.*)
  nodejs                      # the page's script checked (node --check, ctest House.PageScriptParses)
  slurm-wlm munge             # a one-node Slurm cluster for the study test (tests/cluster/, ctest Cluster.*)
)

gf_log() { printf '[godfinger] %s\n' "$*" >&2; }

# Installs the packages of GF_PACKAGES that dpkg does not report as installed.
gf_install_packages() {
  local missing=()
  for pkg in "${GF_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q 'install ok installed' || missing+=("$pkg")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  gf_log "installing missing Debian packages: ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -q
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
}

# What scripts/fuzz needs besides GF_PACKAGES: clang 14 and its libFuzzer.
GF_FUZZ_PACKAGES=(clang-14 libclang-rt-14-dev libfuzzer-14-dev)

# Installs GF_PACKAGES and GF_FUZZ_PACKAGES that dpkg does not report as installed.
gf_install_fuzz_packages() {
  GF_PACKAGES+=("${GF_FUZZ_PACKAGES[@]}")
  gf_install_packages
}

# Configures (first run only) and builds one CMake preset: release, debug, asan-ubsan or tsan.
# GF_BUILD_TARGETS (space-separated) builds only those targets, e.g. the threaded tests for tsan.
gf_build() {
  local preset="$1"
  cd "$GF_ROOT"
  if [ ! -f "build/$preset/build.ninja" ]; then
    cmake --preset "$preset"
  fi
  # shellcheck disable=SC2086 # the targets are words
  cmake --build --preset "$preset" ${GF_BUILD_TARGETS:+--target $GF_BUILD_TARGETS}
}
