# The mathematics of a report.md as a standalone LaTeX document, so that a real TeX engine checks
# every formula (tests/bats/report.bats compiles it with pdflatex -halt-on-error):
#   awk -f latex_document.awk report.md > report.tex
# A display block is the lines between two lines "$$"; inline math is $...$ on any other line
# (a \$ is an escaped dollar, not math). Each becomes its own paragraph, in the report's order.
# A fenced code block (``` or ~~~, closed by a fence of the same character at least as long) and a
# code span (`...`) are text, never mathematics: nothing in them is lifted into the document.
BEGIN {
  print "\\documentclass{article}"
  print "\\usepackage{amsmath}"
  print "\\usepackage{amssymb}"
  print "\\allowdisplaybreaks"
  print "\\begin{document}"
  display = 0
  fence = ""
}
# The run of fence characters a line starts with ("" when it starts with fewer than three).
function fence_of(line,    c, n) {
  c = substr(line, 1, 1)
  if (c != "`" && c != "~") return ""
  n = 0
  while (substr(line, n + 1, 1) == c) n++
  return n >= 3 ? substr(line, 1, n) : ""
}
fence != "" {
  f = fence_of($0)
  if (f != "" && substr(f, 1, 1) == substr(fence, 1, 1) && length(f) >= length(fence) && $0 ~ /^[`~]+[ \t]*$/) fence = ""
  next
}
!display && fence_of($0) != "" { fence = fence_of($0); next }
/^\$\$$/ {
  if (display) { print "\\]"; display = 0 } else { print "\\["; display = 1 }
  next
}
display { print; next }
{
  line = $0
  gsub(/\\\\/, "", line)
  gsub(/\\\$/, "", line)
  gsub(/\\`/, "", line)
  gsub(/`[^`]*`/, "", line)
  while (match(line, /\$[^$]+\$/)) {
    print substr(line, RSTART, RLENGTH) "\\par"
    line = substr(line, RSTART + RLENGTH)
  }
}
END {
  if (display) { print "unterminated display block" > "/dev/stderr"; exit 1 }
  if (fence != "") { print "unterminated code block" > "/dev/stderr"; exit 1 }
  print "\\end{document}"
}
