# Reads the per-pixel dumps of ch10-exact-sphere.patch (see ch10-float-double.md):
#   python3 ch10-float-double.py out/doublex.bin out/double.bin   # which records differ, and how
#   python3 ch10-float-double.py --t out/doublex.bin out/float.bin out/floatx.bin ...  # t errors by sphere level
import collections, struct, sys

def load(path):
    b = open(path, 'rb').read()
    return [struct.unpack_from('iiddddddd', b, 64 * i) for i in range(len(b) // 64)]

def level(i):  # the flake of level 4: object j's sphere level (0: the root)
    if i == 0: return 0
    for lv, block in ((1, 820), (2, 91), (3, 10)):
        i = (i - 1) % block
        if i == 0: return lv
    return 4

if sys.argv[1] == '--t':
    exact = load(sys.argv[2])
    for name in sys.argv[3:]:
        eps = 2.0**-23 if 'float' in name else 2.0**-52
        errors = collections.defaultdict(list)
        for x, y in zip(load(name), exact):
            if x[0] == y[0] and x[0] >= 0: errors[level(x[0])].append(abs(x[2] - y[2]) / y[2] / eps)
        for lv in sorted(errors):
            e = sorted(errors[lv]); n = len(e)
            print(name, 'level', lv, 'median %.1f p99 %.1f max %.1f' % (e[n // 2], e[int(n * .99)], e[-1]))
else:
    a, b = load(sys.argv[1]), load(sys.argv[2])
    kinds = collections.Counter()
    for x, y in zip(a, b):  # lit: -1 light below the surface, 0 shadow ray free, 1 blocked by the flake, 2 by a plane
        kinds['same' if x[:2] == y[:2] else 'object' if x[0] != y[0] else 'shadow %d->%d' % (x[1], y[1])] += 1
    print(kinds)
