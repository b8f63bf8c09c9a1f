# Shared by scripts/setup, scripts/test and scripts/setup-browser-tests (sourced, not run).
# install_debian_packages WHO PKG...: installs the packages that are not installed yet with
# apt-get (as root or through sudo), waiting for another apt-get to finish; `apt-get update` only
# when an install fails. WHO prefixes the messages.
install_debian_packages() {
  local who=$1
  shift
  local missing=() p
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  ((${#missing[@]})) || return 0
  echo "$who: installing Debian packages: ${missing[*]}"
  local sudo=()
  if [[ $(id -u) -ne 0 ]]; then
    command -v sudo >/dev/null || { echo "$who: error: need root or sudo to install: ${missing[*]}" >&2; return 1; }
    sudo=(sudo)
  fi
  local apt=("${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get -o DPkg::Lock::Timeout=600)
  if ! "${apt[@]}" install -y --no-install-recommends "${missing[@]}"; then
    "${apt[@]}" update || { echo "$who: error: apt-get update failed" >&2; return 1; }
    "${apt[@]}" install -y --no-install-recommends "${missing[@]}" || {
      echo "$who: error: could not install: ${missing[*]}" >&2; return 1; }
  fi
}
