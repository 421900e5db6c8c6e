#!/bin/bash
# Counts the checks of which kind of job is at hand (issue 23): the issue's broad grep, and a narrower one.
#   tools/job-kind-checks.sh [TREE] [N]   (TREE: a git work tree, default .; N: how many files to list)
# Then counts, per project, the lines that branch on the kind itself (the broad greps also catch other nullables), and
# lists the front ends' (App and CLI) line by line, file:line: text, so that each can be read with its reason (issue 35).
cd "${1:-.}"
files=$(git ls-files 'src/*.cs' 'src/*.razor')
echo "issue grep (PreparedJob?|PreparedDrawing?|LayeredJob?|is (not )?null): $(grep -hE 'PreparedJob\?|PreparedDrawing\?|LayeredJob\?|is (not )?null' $files | wc -l) lines in $(grep -lE 'PreparedJob\?|PreparedDrawing\?|LayeredJob\?|is (not )?null' $files | wc -l) files"
re='(PreparedJob|PreparedDrawing|LayeredJob|DotPlan)\?|\b(Drawing|Layered|layered|drawing|prepared|Job|Image|Dots|dots)!?(\.[A-Za-z]+)? *(is (not )?null|is \{|!= null|== null|\?\.|\?\?)'
echo "job-kind checks: $(grep -hE "$re" $files | wc -l) lines in $(grep -lE "$re" $files | wc -l) files"
grep -cE "$re" $files | grep -v ':0$' | sort -t: -k2 -nr | head -${2:-12}
# The branches on the kind itself: a type test of a job or program kind, or which of image, drawing, dots or layers is set.
kind='\b(is|case|as) (not )?(RasterJob|DotJob|DrawingJob|LayersJob|SweepJob|RasterProgram|DotProgram|DrawingProgram|RasterPart|DotPart|DrawingPart|ImagePart)\b|\((RasterPart|DotPart|DrawingPart|ImagePart)\)|^\s*(RasterJob|DotJob|DrawingJob|LayersJob|SweepJob|RasterProgram|DotProgram|DrawingProgram|RasterPart|DotPart|DrawingPart|ImagePart)\b.*=>|\b(Drawing|Image|Dots|Layered|drawing|image|dots|layered)(\.[A-Za-z]+)? *(is (not )?null|is \{|!= null|== null|\?\?)'
for part in App Cli Devices Simulator Machines Core; do
  echo "kind branches in $part: $(grep -hE "$kind" $(echo "$files" | grep "^src/LaserEngrave.$part/") 2>/dev/null | wc -l)"
done
echo "kind branches in the front ends, line by line:"
grep -nE "$kind" $(echo "$files" | grep -E "^src/LaserEngrave.(App|Cli)/") 2>/dev/null | sed -E 's/:[[:space:]]+/: /'
