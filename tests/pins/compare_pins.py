# compare_pins.py OLD NEW: every output render_pins.sh left in OLD against NEW's: pixels exact
# in every channel (idiff), metadata equal but for the render's time; checkpoints: every header
# field but the times (render_seconds, judging_seconds), and every pixel record byte for byte.
# Exit 1 if any differs.
import os, subprocess, sys
old, new = sys.argv[1:3]
bad = 0
def meta(path):
    out = subprocess.run(["oiiotool", "--info", "-v", "-a", path], capture_output=True, text=True).stdout
    # the path's column is padded to its length: compare the words, not the spaces
    return [" ".join(l.replace(path, "X").split()) for l in out.splitlines()[1:]
            if "render_seconds" not in l]
for name in sorted(os.listdir(old)):
    a, b = os.path.join(old, name), os.path.join(new, name)
    if name in ("log", "sums.txt"): continue
    if not os.path.exists(b): print("MISSING", name); bad += 1; continue
    if name.endswith(".checkpoint"):
        A, B = open(a, "rb").read(), open(b, "rb").read()
        ha, ra = A.split(b"end\n", 1); hb, rb = B.split(b"end\n", 1)
        times = (b"render_seconds", b"judging_seconds")
        fa = [l for l in ha.split(b"\n") if not l.startswith(times)]
        fb = [l for l in hb.split(b"\n") if not l.startswith(times)]
        same = fa == fb and ra[:-8] == rb[:-8]
        print(("same    " if same else "DIFFERS ") + name, len(ra)); bad += not same; continue
    r = subprocess.run(["idiff", "-a", "-fail", "0", "-failpercent", "0", "-warn", "0", a, b], capture_output=True, text=True)
    pixels = r.returncode == 0
    m = meta(a) == meta(b)
    print(("same    " if pixels and m else "DIFFERS ") + name + ("" if pixels else " (pixels)") + ("" if m else " (metadata)"))
    bad += not (pixels and m)
print("differing:", bad)
sys.exit(1 if bad else 0)
