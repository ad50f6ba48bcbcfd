#!/usr/bin/env bash
# run_cli_case.sh: runs one command-line case of `raydrive` in a fresh temporary directory
# and checks its exit code, its stderr, and what it left behind.
#
# usage: run_cli_case.sh [options] EXPECTED_RC STDERR_REGEX NOT_EXIST COMMAND [ARGS...]
#   EXPECTED_RC   exit code COMMAND must return
#   STDERR_REGEX  extended regex (grep -Ez: the whole stderr is one text, so `.` also
#                 matches newlines) that stderr must match; '-' for no check
#   NOT_EXIST     glob, relative to the temp dir, that must match nothing afterwards; '-'
#                 for no check
# options (each may repeat; checks run after COMMAND, in the order given):
#   --bin PATH          the raydrive binary, exported as $RAYDRIVE for --pre/--post
#   --pre SHELL         run SHELL (bash -c) in the temp dir before COMMAND; must exit 0
#   --post SHELL        run SHELL (bash -c) in the temp dir after COMMAND; must exit 0
#   --stdout REGEX      stdout must match REGEX (grep -Ez, as for stderr)
#   --exists FILE       FILE must exist; a *.exr must start with the OpenEXR magic 76 2f 31 01
#   --absent GLOB       GLOB must match nothing
#   --json FILE EXPR    python3 EXPR over d = json.load(FILE) (os and json imported) is true
#   --skip-if-root      skip the case (exit 77) when run as root
#
# Every *.rib beside this script is copied into the temp dir first, so COMMAND names
# scenes by their bare names (and diagnostics read `bad_request.rib:3: ...`).
# RAYDRIVE_CACHE_DIR points into the temp dir and RAYDRIVE_DEVICE is unset. The temp dir
# is removed on success and kept (and named) on failure.
set -u

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
checks=()   # encoded as kind<TAB>arg1<TAB>arg2
pres=()
export RAYDRIVE="${RAYDRIVE:-raydrive}"

while [[ $# -gt 0 && "$1" == --* ]]; do
    case "$1" in
        --bin) RAYDRIVE="$2"; export RAYDRIVE; shift 2 ;;
        --pre) pres+=("$2"); shift 2 ;;
        --post) checks+=("post"$'\t'"$2"$'\t'); shift 2 ;;
        --stdout) checks+=("stdout"$'\t'"$2"$'\t'); shift 2 ;;
        --exists) checks+=("exists"$'\t'"$2"$'\t'); shift 2 ;;
        --absent) checks+=("absent"$'\t'"$2"$'\t'); shift 2 ;;
        --json) checks+=("json"$'\t'"$2"$'\t'"$3"); shift 3 ;;
        --skip-if-root)
            if [[ "$(id -u)" == 0 ]]; then
                echo "SKIP: running as root, file permissions are not enforced"
                exit 77
            fi
            shift ;;
        *) echo "run_cli_case.sh: unknown option $1" >&2; exit 2 ;;
    esac
done
if [[ $# -lt 4 ]]; then
    echo "usage: run_cli_case.sh [options] EXPECTED_RC STDERR_REGEX NOT_EXIST COMMAND..." >&2
    exit 2
fi
expected_rc="$1" stderr_re="$2" not_exist="$3"
shift 3

work="$(mktemp -d "${TMPDIR:-/tmp}/raydrive-cli.XXXXXX")" || exit 2
cp "$here"/*.rib "$work"/
cd "$work" || exit 2
export RAYDRIVE_CACHE_DIR="$work/cache"
unset RAYDRIVE_DEVICE RAYDRIVE_NO_CACHE

failures=0
fail() {
    echo "FAIL: $*"
    failures=$((failures + 1))
}

# Does GLOB (relative to the temp dir) match any path? Lists the matches.
glob_matches() {
    local -a m=() all
    local f
    shopt -s nullglob dotglob
    # shellcheck disable=SC2206
    all=($1)
    shopt -u nullglob dotglob
    for f in "${all[@]+"${all[@]}"}"; do
        [[ -e "$f" || -L "$f" ]] && m+=("$f")
    done
    [[ ${#m[@]} -gt 0 ]] && printf '%s\n' "${m[@]}"
    [[ ${#m[@]} -gt 0 ]]
}

for p in "${pres[@]+"${pres[@]}"}"; do
    echo "+ (pre) $p"
    if ! bash -c "$p" >pre.out 2>&1; then
        cat pre.out
        fail "pre-command failed: $p"
    fi
done

echo "+ $*"
"$@" >stdout.txt 2>stderr.txt
rc=$?
echo "--- exit code: $rc (expected $expected_rc)"
echo "--- stderr:"; cat stderr.txt
echo "--- stdout:"; cat stdout.txt
echo "---"

[[ "$rc" == "$expected_rc" ]] || fail "exit code $rc, expected $expected_rc"
if [[ "$stderr_re" != "-" ]] && ! grep -Ezq -- "$stderr_re" stderr.txt; then
    fail "stderr does not match /$stderr_re/"
fi
if [[ "$not_exist" != "-" ]] && glob_matches "$not_exist"; then
    fail "'$not_exist' exists but must not"
fi

for c in "${checks[@]+"${checks[@]}"}"; do
    IFS=$'\t' read -r kind a b <<<"$c"
    case "$kind" in
        stdout)
            grep -Ezq -- "$a" stdout.txt || fail "stdout does not match /$a/" ;;
        exists)
            if [[ ! -f "$a" ]]; then
                fail "$a was not written"
            elif [[ "$a" == *.exr ]]; then
                magic="$(head -c 4 "$a" | od -An -tx1 | tr -d ' \n')"
                [[ "$magic" == "762f3101" ]] || fail "$a does not start with the OpenEXR magic (got $magic)"
            fi ;;
        absent)
            if glob_matches "$a"; then fail "'$a' exists but must not"; fi ;;
        json)
            python3 - "$a" "$b" <<'PY' || fail "$a: $b"
import json, os, sys
path, expr = sys.argv[1], sys.argv[2]
try:
    with open(path) as f:
        d = json.load(f)
except Exception as e:
    print(f"cannot read {path}: {e}")
    sys.exit(1)
try:
    ok = eval(expr, {"json": json, "os": os, "d": d})
except Exception as e:
    print(f"{expr}: raised {type(e).__name__}: {e}")
    sys.exit(1)
sys.exit(0 if ok else 1)
PY
            ;;
        post)
            echo "+ (post) $a"
            bash -c "$a" || fail "post-check failed: $a" ;;
    esac
done

if [[ $failures -gt 0 ]]; then
    echo "$failures check(s) failed; kept $work"
    exit 1
fi
cd / && rm -rf "$work"
echo "PASS"
exit 0
