# Sourced by the scripts and .ci/run: `need_packages PKG...` installs the Debian packages
# named that are not installed yet (apt-get, as root or through sudo), saying which.
need_packages() {
  local missing="" p sudo_cmd=""
  for p in "$@"; do
    dpkg -s "$p" >/dev/null 2>&1 || missing="$missing $p"
  done
  [ -z "$missing" ] && return 0
  echo "== installing:$missing" >&2
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  # shellcheck disable=SC2086
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq $missing
}
