#!/usr/bin/env bash
# Checks the bash completion against the built binary (a CTest test):
#   test_completion.sh SOMBRA
set -euo pipefail
sombra="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"
folder="$(mktemp -d)"
trap 'rm -rf "$folder"' EXIT
ln -s "$sombra" "$folder/sombra"
PATH="$folder:$PATH"
source "$(dirname "${BASH_SOURCE[0]}")/sombra.bash"

fail() { echo "test_completion.sh: $*" >&2; exit 1; }
# complete WORD... : COMPREPLY for the last word, space-separated.
complete_words() {
    COMP_WORDS=("$@")
    COMP_CWORD=$(($# - 1))
    COMPREPLY=()
    _sombra
    echo "${COMPREPLY[*]}"
}
[ "$(complete_words sombra ren)" = render ] || fail "'sombra ren' does not complete to render"
[ "$(complete_words sombra render --wid)" = --width ] || fail "'--wid' does not complete to --width"
[ "$(complete_words sombra render --tone)" = --tonemap ] || fail "'--tone' does not complete to --tonemap"
[ "$(complete_words sombra render s.json --tonemap '')" = "none pbr-neutral" ] || fail "--tonemap's values"
[ "$(complete_words sombra explain --sam)" = --sample ] || fail "explain's --sample"
[ -z "$(complete_words sombra merge --crop)" ] || fail "merge has no --crop, yet it was offered"
touch "$folder/scene-one.json"
[ "$(complete_words sombra render "$folder/scene-o")" = "$folder/scene-one.json" ] || fail "files"
echo "test_completion.sh: bash completion OK"
