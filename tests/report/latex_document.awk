# The mathematics of a report.md as a standalone LaTeX document, so that a real TeX engine checks
# every formula (tests/bats/report.bats compiles it with pdflatex -halt-on-error):
#   awk -f latex_document.awk report.md > report.tex
# A display block is the lines between two lines "$$"; inline math is $...$ on any other line
# (a \$ is an escaped dollar, not math). Each becomes its own paragraph, in the report's order.
BEGIN {
  print "\\documentclass{article}"
  print "\\usepackage{amsmath}"
  print "\\usepackage{amssymb}"
  print "\\allowdisplaybreaks"
  print "\\begin{document}"
  display = 0
}
/^\$\$$/ {
  if (display) { print "\\]"; display = 0 } else { print "\\["; display = 1 }
  next
}
display { print; next }
{
  line = $0
  gsub(/\\\$/, "", line)
  while (match(line, /\$[^$]+\$/)) {
    print substr(line, RSTART, RLENGTH) "\\par"
    line = substr(line, RSTART + RLENGTH)
  }
}
END {
  if (display) { print "unterminated display block" > "/dev/stderr"; exit 1 }
  print "\\end{document}"
}
