# Shared by the scripts: installs the system packages gendpde builds with.
install_build_deps() {
  if ! command -v cargo >/dev/null; then
    echo "cargo is missing: install the Rust toolchain (https://rustup.rs)" >&2
    exit 1
  fi
  local missing=()
  command -v cc >/dev/null || missing+=(build-essential)
  command -v mpirun >/dev/null || missing+=(openmpi-bin)
  [ -e /usr/include/x86_64-linux-gnu/openmpi ] || [ -e /usr/lib/x86_64-linux-gnu/openmpi/include ] || missing+=(libopenmpi-dev)
  command -v clang >/dev/null || missing+=(clang)
  ldconfig -p | grep -q libclang || missing+=(libclang-dev)
  command -v pkg-config >/dev/null || missing+=(pkg-config)
  [ -e /usr/include/hdf5/serial/hdf5.h ] || missing+=(libhdf5-dev)
  command -v pip3 >/dev/null || command -v pip >/dev/null || missing+=(python3-pip)
  if [ ${#missing[@]} -gt 0 ]; then
    local sudo_cmd=""
    [ "$(id -u)" = 0 ] || sudo_cmd="sudo"
    echo "installing: ${missing[*]}" >&2
    $sudo_cmd apt-get update -qq
    $sudo_cmd env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${missing[@]}" >/dev/null
  fi
  # h5py and friends for the H5MD reader, the Python package and its tests; OVITO and
  # MDAnalysis for the tests that open dumps and H5MD files as users do.
  if ! python3 -c "import h5py, numpy, matplotlib, pandas, pytest, ovito, MDAnalysis" 2>/dev/null; then
    python3 -m pip install -q -r "$(dirname "${BASH_SOURCE[0]}")/requirements.txt" 2>/dev/null \
      || python3 -m pip install -q --break-system-packages -r "$(dirname "${BASH_SOURCE[0]}")/requirements.txt"
  fi
  # OpenMPI refuses to start as root unless told it may.
  if [ "$(id -u)" = 0 ]; then
    export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  fi
}
