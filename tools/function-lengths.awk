# Prints "FILE:LINE NAME LENGTH" for every function whose body is longer than `max` lines.
# A function starts at a line at column 0 that begins a signature (a name and a parenthesis,
# not a namespace, type or variable) and whose signature ends in "{" on that line or on the
# indented lines after it; its body runs to the next "}" at column 0 (the layout of this code,
# which .clang-format keeps).
#
#   awk -v max=80 -f tools/function-lengths.awk FILES...
FNR == 1 { inside = 0; candidate = 0 }
inside {
  if ($0 ~ /^\}/) {
    inside = 0
    len = FNR - start - 1
    if (len > max) printf "%s:%d %s %d\n", FILENAME, start, name, len
  }
  next
}
/^[A-Za-z_~].*\(/ && $0 !~ /^(namespace|struct|class|enum|union|extern|using|typedef|template|static_assert|#)/ &&
    $0 !~ /^[^(]*=/ {
  candidate = FNR
  name = $0
  sub(/\(.*/, "", name)
  n = split(name, w, " ")
  name = w[n]
}
candidate && /\{$/ && $0 !~ /;/ {
  if (FNR == candidate || $0 ~ /^[ \t]/) { inside = 1; start = FNR; candidate = 0; next }
}
candidate && FNR > candidate && $0 !~ /^[ \t]/ { candidate = 0 }
