# Writes tests/data/string_chain15.toml (issue 26, item 3): python3 string_chain.py > string_chain15.toml
n = 15
out = []
out.append('''# Fifteen blocks hanging one below the other on pairs of strings (issue 26, item 3).
# The strings of every pair lie in the x-z plane; a horizontal force along x acts on the top
# block and a sensor measures the top block's x displacement. By mirror symmetry in the x-z
# plane the in-plane motion (one swing per block: 15 modes, 30 states) is decoupled from the
# out-of-plane motion (45 modes, 90 states), which neither the force nor the sensor touches:
# the minimal order is 30 of 120.

[model]
name = "string_chain15"
gravity = [0, 0, "-g"]

[parameters]
m = { value = 1, unit = "kg", description = "mass of each block", range = "> 0" }
g = { value = 9.81, unit = "m/s^2", description = "gravity", range = "> 0" }
l = { value = 0.5, unit = "m", description = "string length", range = "> 0" }
a = { value = 0.2, unit = "m", description = "half the distance between the strings of a pair", range = "> 0" }
h = { value = 0.05, unit = "m", description = "half the height of a block", range = "> 0" }
w = { value = 0.15, unit = "m", description = "half the depth of a block (along y)", range = "> 0" }
''')
# Block k (1..n): centre at z = -k*(l + 2h) + h, top face at centre + h.
def zc(k):
    return f"-{k}*(l + 2*h) + h"
for k in range(1, n + 1):
    out.append(f'''[[body]]
name = "block{k}"
at = [0, 0, "{zc(k)}"]
mass = "m"
moments = ["m*(w^2 + h^2)/3", "m*(a^2 + h^2)/3", "m*(a^2 + w^2)/3"]
''')
for k in range(1, n + 1):
    above = "ground" if k == 1 else f"block{k-1}"
    top = f"{zc(k)} + h"
    bottom = "0" if k == 1 else f"{zc(k-1)} - h"
    for side, sx in (("front", "a"), ("rear", "-a")):
        out.append(f'''[[link]]
name = "string{k}_{side}"
between = ["block{k}", "{above}"]
ends = [["{sx}", 0, "{top}"], ["{sx}", 0, "{bottom}"]]
''')
out.append(f'''[[actuator]]
name = "push"
between = ["block1", "ground"]
ends = [[0, 0, "{zc(1)}"], [-1, 0, "{zc(1)}"]]

[[sensor]]
name = "x1"
between = ["block1", "ground"]
ends = [[0, 0, "{zc(1)}"], [-1, 0, "{zc(1)}"]]
''')
print("\n".join(out))
