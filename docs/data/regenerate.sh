#!/usr/bin/env bash
# Rerun the commands whose output docs/data holds, in order, from the repository root, with
# the hubvib (and python) of the current environment: each entry's commands are the
# "command" list of docs/data/<entry>.meta.json; a folder entry with a "keep" list keeps only
# those files of what its commands wrote. Prints each command and its seconds.
#
#   docs/data/regenerate.sh                 every entry (the benchmark alone takes ~30 min)
#   docs/data/regenerate.sh raba118_signal  only the entries named
#   docs/data/regenerate.sh --stale         every entry the docs build fails on: stale (its
#                                           "source_key" not the current code's) or with no
#                                           key (python docs/generate.py --stale lists them)
#   docs/data/regenerate.sh --list [--stale | ENTRY ...]
#                                           print the entries it would rerun, in order; run none
#
# After an entry's commands, its meta file gets the source key of the code that wrote it
# ("source_key": the docs build and tests/docs fail while it is not the current one, or
# missing unless docs/generate.py UNKEYED_EXEMPT names the entry); at the end the generated
# blocks of every page are refilled (python docs/generate.py --write; REFILL=0 leaves that
# out, to rerun entries one call at a time and refill once after the last).
# Then record the date and the hubvib version in the entry's "measured".
set -euo pipefail
cd "$(dirname "$0")/../.."
PYTHON=${PYTHON:-python}
REFILL=${REFILL:-1}

# cheap first (fe_substructure.json reads raba118_crack's committed run: after it); every
# docs/data entry once (tests/docs/test_docs_site.py checks the list)
ENTRIES=(
  raba118_signal
  raba118_signal_noise0.5
  raba118_signal_noise2
  raba118_signal_planet_error
  stiffness_10mm.json
  convergence
  records
  elastic_identification.json
  record_loop.json
  raba118_crack_path
  diagnosis
  convergence_work
  elastic_ring.json
  raba118_crack
  fe_substructure.json
  floquet_change.json
  crack_path
  raba118_crack_3d_small
  crack_path_backup_ratio
  benchmark.json
)

meta() {  # meta ENTRY FIELD: the field's lines (a list field one item per line)
  "$PYTHON" -c 'import json, sys
value = json.load(open(sys.argv[1])).get(sys.argv[2], [])
print("\n".join(value))' "docs/data/$1.meta.json" "$2"
}

list_only=0
if [[ ${1:-} == --list ]]; then list_only=1; shift; fi
selected=("${ENTRIES[@]}")
if [[ ${1:-} == --stale ]]; then
  (($# == 1)) || { echo "regenerate.sh: --stale takes no entry names" >&2; exit 2; }
  mapfile -t wanted < <("$PYTHON" docs/generate.py --stale)
  selected=()
  for entry in "${ENTRIES[@]}"; do  # in the cheap-first order, then any entry not listed
    if [[ " ${wanted[*]} " == *" $entry "* ]]; then selected+=("$entry"); fi
  done
  for entry in "${wanted[@]}"; do
    if [[ -n $entry && " ${ENTRIES[*]} " != *" $entry "* ]]; then selected+=("$entry"); fi
  done
elif (($#)); then
  selected=("$@")
fi
if ((list_only)); then
  if ((${#selected[@]})); then printf '%s\n' "${selected[@]}"; fi
  exit 0
fi
if ((${#selected[@]} == 0)); then echo "regenerate.sh: no entry to rerun"; exit 0; fi
for entry in "${selected[@]}"; do
  [[ -f docs/data/$entry.meta.json ]] || { echo "regenerate.sh: no docs/data/$entry.meta.json" >&2; exit 2; }
  while IFS= read -r command; do
    [[ -n $command ]] || continue
    echo "+ $command"
    start=$(date +%s)
    bash -c "$command" </dev/null
    echo "  $(($(date +%s) - start)) s"
  done < <(meta "$entry" command)
  mapfile -t keep < <(meta "$entry" keep)
  if ((${#keep[@]})) && [[ -n ${keep[0]} ]]; then
    for path in "docs/data/$entry"/* "docs/data/$entry"/.[!.]*; do
      [[ -e $path ]] || continue
      name=${path##*/}
      [[ " ${keep[*]} " == *" $name "* ]] || rm -rf -- "$path"
    done
  fi
  "$PYTHON" docs/generate.py --record-source "$entry"
done
if [[ $REFILL != 0 ]]; then
  echo "+ python docs/generate.py --write"
  "$PYTHON" docs/generate.py --write
fi
