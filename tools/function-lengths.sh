#!/usr/bin/env bash
# Prints "FILE:LINE NAME LENGTH" for every function definition whose body is longer than MAX
# lines, found by a parser (Universal Ctags), not by the layout: member functions defined inside a
# class, inline functions in headers and functions in namespaces all count. NAME is the function
# qualified by its class (Reader::add_stem, ColorPipeline::Impl::find_xyz; namespaces and
# anonymous scopes left out); LENGTH the lines between the definition's first line and its
# closing brace. Lambdas count as part of the function they are in.
#
#   tools/function-lengths.sh MAX FILES...
set -euo pipefail
max=$1; shift
[ "$#" -eq 0 ] && exit 0
ctags --language-force=C++ --c++-kinds=f --fields=+neZ -o - "$@" |
  awk -F'\t' -v max="$max" '
    $1 ~ /^__anon/ { next }
    {
      line = 0; end = 0; scope = ""
      for (i = 4; i <= NF; i++) {
        if ($i ~ /^line:/) line = substr($i, 6)
        else if ($i ~ /^end:/) end = substr($i, 5)
        else if ($i ~ /^scope:(class|struct|union):/) { scope = $i; sub(/^scope:[a-z]+:/, "", scope) }
      }
      if (end - line - 1 <= max) next
      # The class path without namespaces: the parts from the first capitalised one on.
      n = split(scope, part, "::"); name = ""
      for (j = 1; j <= n; j++) {
        if (part[j] ~ /^__anon/ || (name == "" && part[j] !~ /^[A-Z]/)) continue
        name = name part[j] "::"
      }
      printf "%s:%d %s%s %d\n", $2, line, name, $1, end - line - 1
    }' | sort -t: -k1,1 -k2,2n
