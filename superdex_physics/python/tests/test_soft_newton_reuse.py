"""Soft bodies: Newton iterations reuse the element Hessians of elements that hardly deformed
(SolverParams.implicit_step.soft_hessian_reuse_strain), and the factorization of an earlier iteration: after
the first, an iteration's Newton system is solved by conjugate gradients preconditioned by the
last factorization (SolverStats.soft_factorizations counts the factorizations).

Only the Newton direction is approximate: the gradient, the problem and its stopping test are
unchanged. A soft block pinned at its base, pressed by a rigid sphere on a vertical slider, is
stepped with reuse (the default) and without it (0: every element that moved is recomputed):

- the two runs reach the same states and the same contact forces: the ball's height within
  1e-6 m, the nodes within 1e-5 m and the force within 0.5 % of the press. The pressed block's
  equilibrium is not unique to the micrometre (its elastic energy is not convex), so runs whose
  Newton iterations take different paths may settle a few micrometres apart: in double, two
  runs without reuse, one with every linear solve direct and one with conjugate gradients, end
  5 micrometres apart in a 2 mm dent, where the run with reuse agrees with the direct one;
- the reuse does not cost Newton iterations (a few more in total at most);
- it computes far fewer element Hessians (SolverStats.soft_element_hessians): at least one pass
  over every element per step (at the start of the step) and, after it, only the elements under
  the sphere, where the run without reuse recomputes every element that moved at every iteration;
- the sphere's reaction equals the applied force plus its weight once it rests (momentum balance);
- fewer factorizations than Newton iterations: most iterations after a step's first are solved
  by the preconditioned conjugate gradients, also without element reuse, where every
  iteration's matrix differs from the factored one.
"""

import numpy as np
import pytest

import superdex.physics as sdp
from conftest import articulation, joint, link, node_positions_world
from test_soft_contact import soft_block

DT, STEPS = 0.004, 60
PUSH, MASS, RADIUS = 2.0, 0.02, 0.02


def press(reuse_strain):
    """Steps the pressed block; returns per-step stats and the final state."""
    scene = sdp.create_scene("reuse")
    scene.set_gravity([0, 0, -9.81])
    params = scene.get_solver_params()
    params.implicit_step.soft_hessian_reuse_strain = reuse_strain
    scene.set_solver_params(params)
    block, nodes = soft_block(scene, size=0.1, cells=5, E=1e5)
    links = [link("base", mass=1.0, moment_of_inertia=[1e-3, 0, 0, 1e-3, 0, 1e-3]),
             link("ball", parent=0, mass=MASS, moment_of_inertia=[1e-6, 0, 0, 1e-6, 0, 1e-6],
                  shape=sdp.create_sphere_shape([0, 0, 0], RADIUS))]
    joints = [joint("weld", "hard", at=[0, 0, 0.1 + RADIUS + 0.001]),
              joint("slide", "prismatic", axis=[0, 0, 1])]
    slider = articulation(scene, "slider", links, joints)
    ball = scene.get_actor(slider.get_nested_link_actors()[1])
    ball.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
    slider.set_external_forces_on_dofs([0], [-PUSH])
    hessians, iterations, factorizations = [], [], []
    for _ in range(STEPS):
        scene.step(DT)
        stats = scene.get_solver_stats()
        assert stats.convergence_status == sdp.ConvergenceStatus.CONVERGED
        hessians.append(stats.soft_element_hessians)
        iterations.append(stats.total_non_linear_iters)
        factorizations.append(stats.soft_factorizations)
    result = {"x": node_positions_world(block), "ball_z": float(ball.get_root_transform().translation[2]),
              "force": np.array(ball.get_contact_force_world(), dtype=float), "hessians": np.array(hessians),
              "iterations": np.array(iterations), "factorizations": np.array(factorizations), "tets": 6 * 5**3}
    sdp.destroy_scene(scene)
    return result


def test_reused_element_hessians_give_the_same_steps_for_fewer_hessians(engine):
    default = sdp.SolverParams().implicit_step.soft_hessian_reuse_strain
    reused, exact = press(default), press(0.0)
    assert default > 0
    # the same motion (the block dents by about 2 mm under the ball)
    assert reused["ball_z"] == pytest.approx(exact["ball_z"], abs=1e-6)
    np.testing.assert_allclose(reused["x"], exact["x"], rtol=0, atol=1e-5)
    # the same contact force within 0.5 % of the press (its small tangential part, static
    # friction, is as sensitive to the last micrometre as any sticking contact)
    np.testing.assert_allclose(reused["force"], exact["force"], rtol=0, atol=5e-3 * PUSH)
    # at rest, the sphere's reaction balances the push and its weight
    assert reused["force"][2] == pytest.approx(PUSH + MASS * 9.81, rel=0.02)
    # no more Newton iterations than without reuse, but a few
    assert reused["iterations"].sum() <= exact["iterations"].sum() + STEPS // 10
    # every step computes each element at its start; without reuse every iteration after the
    # first recomputes the elements that moved, with it only a fraction of them
    tets = reused["tets"]
    assert (reused["hessians"] >= tets).all() and (exact["hessians"] >= tets).all()
    extra_reused = (reused["hessians"] - tets).sum()
    extra_exact = (exact["hessians"] - tets).sum()
    assert extra_exact > STEPS * tets // 2, "without reuse, later iterations recompute the moving elements"
    assert extra_reused < 0.25 * extra_exact


def test_later_newton_iterations_are_solved_by_preconditioned_cg(engine):
    # without element reuse every later iteration's matrix differs from the factored one (a
    # matrix equal to it bit for bit would keep its factor in any case)
    run = press(0.0)
    # every step factors at least once (its first iteration), and most later iterations do not
    assert (run["factorizations"] >= 1).all()
    later = (run["iterations"] - 1).sum()
    assert later > STEPS // 2
    assert (run["factorizations"] - 1).sum() < 0.25 * later
    assert run["force"][2] == pytest.approx(PUSH + MASS * 9.81, rel=0.02)


def test_reuse_strain_is_validated(scene):
    params = scene.get_solver_params()
    for bad in (-1e-3, float("nan"), float("inf")):
        params.implicit_step.soft_hessian_reuse_strain = bad
        with pytest.raises(sdp.Error, match="implicit_step.soft_hessian_reuse_strain"):
            scene.set_solver_params(params)
