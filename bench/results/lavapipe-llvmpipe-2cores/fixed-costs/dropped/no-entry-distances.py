# usage: python3 no-entry-distances.py SHADER_DIR: the edit measured in no-entry-distances.txt
import sys, re
p = sys.argv[1] + "/include/bvh_traversal.glsl"
s = open(p).read()
s, n1 = re.subn(r"haveRef = anyHit \|\| !\(stackEnter\[top\] > best\.t \* kRoundingSlack\);", "haveRef = true;", s)
s, n2 = re.subn(r"if \(!anyHit\) stackEnter\[top\] = enter;", "", s)
assert n1 == 1 and n2 == 1, (n1, n2)
open(p, "w").write(s)
