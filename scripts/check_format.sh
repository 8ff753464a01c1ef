#!/usr/bin/env bash
# The C++ lines a change touches, checked against .clang-format: only the lines
# added or changed since BASE (clang-format-diff), so code that predates the
# style file never needs a reformat and a change is held to it line by line.
#   scripts/check_format.sh [BASE]   exit 0: formatted; 1: prints the diff
#                                    that would format them; 2: no clang-format
# BASE (or FORMAT_BASE) is any commit; without one, the branch's fork point
# from origin/main (or main), that is the whole change a branch brings; on main
# itself (fork point = HEAD), the last commit. Uncommitted edits count too.
# Apply the fix with: git diff -U0 BASE | clang-format-diff-14 -p1 -i
set -euo pipefail
cd "$(dirname "$0")/.."

CLANG_FORMAT=$(command -v clang-format-14 || command -v clang-format || true)
FORMAT_DIFF=$(command -v clang-format-diff-14 || command -v clang-format-diff || true)
if [[ -z $CLANG_FORMAT || -z $FORMAT_DIFF ]]; then
  echo "check_format: clang-format and clang-format-diff not found (scripts/setup.sh installs clang-format)" >&2
  exit 2
fi

commit_exists() { git rev-parse --verify --quiet "$1^{commit}" >/dev/null; }
base=${1:-${FORMAT_BASE:-}}
if [[ -z $base ]]; then
  for upstream in origin/main main; do
    if commit_exists "$upstream"; then
      base=$(git merge-base HEAD "$upstream" || true)
      [[ -n $base ]] && break
    fi
  done
  # On main itself the fork point is HEAD: the change is the last commit.
  if [[ -z $base || $base == "$(git rev-parse HEAD)" ]]; then
    base=""
    commit_exists HEAD~1 && base=HEAD~1
  fi
fi
if [[ -z $base ]]; then
  # A shallow clone of one commit, or a repository of one commit: no change
  # can be told apart from the code that was there.
  echo "check_format: no base commit to compare with (shallow clone?); nothing checked" >&2
  exit 0
fi
if ! commit_exists "$base"; then
  echo "check_format: $base is not a commit" >&2
  exit 2
fi

echo "check_format: C++ lines changed since $(git rev-parse --short "$base") ($base)"
# -M: a renamed file counts by the lines its move changed, not as all new.
fixes=$(git diff -M -U0 --no-color "$base" -- '*.cpp' '*.hpp' '*.h' '*.cc' |
  "$FORMAT_DIFF" -p1 -binary "$CLANG_FORMAT" -style file)
if [[ -n $fixes ]]; then
  printf '%s\n' "$fixes"
  echo "check_format: the lines above differ from .clang-format; fix with" >&2
  echo "  git diff -U0 $base | $(basename "$FORMAT_DIFF") -p1 -i" >&2
  exit 1
fi
echo "check_format: formatted"
