"""The five-box stack of test_contact_stack.py, settled in SuperDex and in MuJoCo: same resting heights.

Both simulators get the same scene: a ground plane at z = 0, five free 1 kg cubes of half
extent 0.1 m with friction 0.5 (MuJoCo combines friction by max, SuperDex by the geometric
mean: with every surface at 0.5 both give 0.5), gravity -9.81 z, timestep 10 ms, box k released at
z = 0.1 + 0.2 k + 0.001 (k + 1). After 3 s every box's height must agree within 3 mm.

MuJoCo contact parameters: MuJoCo contacts are soft; with its defaults (solref 0.02 1,
solimp 0.9 0.95 0.001) this stack sinks ~2 mm at the top. We use solref = (0.02, 1), the
stiffest time constant MuJoCo accepts at this timestep (it clamps timeconst to >= 2 timestep),
critically damped, and solimp = (0.99, 0.99, 0.001): impedance 0.99 at all penetrations, so
the steady penetration per contact is ~(1 - d)/d g / k ~ 0.04 mm and the stack sinks about
0.25 mm in total: close to the rigid contact SuperDex models by default. The Newton solver
with a tight tolerance and elliptic friction cones (SuperDex's cone is elliptic too) keeps the
reference clean; the test also checks the reference itself rests within 1 mm of the ideal
heights 0.1 + 0.2 k, so a disagreement points at SuperDex.
"""

import numpy as np

try:
    import mujoco
except ImportError as exc:  # a declared dev dependency: missing means a broken environment, not a skip
    raise ImportError(
        "mujoco (a dev dependency in pyproject.toml) is required by this test; run `uv sync` to install it"
    ) from exc

from contact_helpers import add_box, add_ground, position, step_for

N = 5
M = 1.0
HALF = 0.1
GAP = 1e-3
MU = 0.5
DT = 0.01
SETTLE = 3.0


def start_height(k):
    return HALF + 2 * HALF * k + GAP * (k + 1)


def mujoco_stack_model():
    bodies = "\n".join(
        f'    <body name="box{k}" pos="0 0 {start_height(k)!r}"><freejoint/>'
        f'<geom type="box" size="{HALF} {HALF} {HALF}" mass="{M}"/></body>'
        for k in range(N))
    xml = f"""
<mujoco model="five box stack">
  <option timestep="{DT}" gravity="0 0 -9.81" integrator="Euler" cone="elliptic" solver="Newton"
          iterations="200" tolerance="1e-12"/>
  <default>
    <geom friction="{MU} 0.005 0.0001" solref="0.02 1" solimp="0.99 0.99 0.001"/>
  </default>
  <worldbody>
    <geom name="ground" type="plane" size="0 0 1"/>
{bodies}
  </worldbody>
</mujoco>"""
    return mujoco.MjModel.from_xml_string(xml)


def mujoco_resting_heights():
    model = mujoco_stack_model()
    data = mujoco.MjData(model)
    for _ in range(int(round(SETTLE / DT))):
        mujoco.mj_step(model, data)
    assert np.all(np.abs(model.body_mass[1:] - M) < 1e-12)
    return np.array([data.xpos[model.body(f"box{k}").id][2] for k in range(N)])


def test_stack_resting_heights_match_mujoco(scene):
    """Every box's resting height after 3 s is within 3 mm of MuJoCo's (and MuJoCo's own heights
    are within 1 mm of the rigid ideal 0.1 + 0.2 k, so the reference is sound)."""
    reference = mujoco_resting_heights()
    ideal = HALF + 2 * HALF * np.arange(N)
    np.testing.assert_allclose(reference, ideal, atol=1e-3, err_msg="the MuJoCo reference itself is off")

    add_ground(scene, mu=MU)
    boxes = [add_box(scene, f"box{k}", [0, 0, start_height(k)], half=HALF, mass=M, mu=MU) for k in range(N)]
    step_for(scene, DT, SETTLE)
    heights = np.array([position(b)[2] for b in boxes])
    np.testing.assert_allclose(heights, reference, atol=3e-3)
