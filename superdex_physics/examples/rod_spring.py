"""A helical spring made of an elastic rod, holding a block.

A steel-like wire (radius 2 mm) is coiled into a spring of 8 turns on a 40 mm diameter, its axis
vertical; at each end a straight lead runs from the coil to the axis. The top lead's end is held by
a node position constraint and, through an element rotation constraint, to a static anchor block;
a 4 kg block hangs from the bottom lead's end, tied to its last node and to its last element's
frame. The rod's stretching, bending and twisting all act: a close-coiled spring carries its load by
twisting its wire, and its stiffness is G d^4 / (8 D^3 n) (wire diameter d, coil diameter D, n
turns). The script lets the block settle and prints how far it dropped against the load over that
stiffness (the block's weight, the bottom lead's and half the coil's own).

Run: uv run python superdex_physics/examples/rod_spring.py [--seconds 2] [--dt 0.005]

Add --debugger to watch it in the scene debugger; without a display, also set
SUPERDEX_DEBUGGER_RECORD=spring.jsonl to record the run to a file.
"""

import argparse
import math

import numpy as np

import superdex.physics as sdp

ex = sdp.experimental
G = 9.81
WIRE_RADIUS = 0.002          # m
COIL_DIAMETER = 0.04         # m, D
TURNS = 8                    # n
PITCH = 0.01                 # m of height per turn (the coil is close: pitch angle under 5 degrees)
NODES_PER_TURN = 32
LEAD_NODES = 4               # elements on each straight lead, from the coil to the axis
YOUNGS_MODULUS = 2e11        # Pa
SHEAR_MODULUS = 8e10         # Pa
DENSITY = 7800.0             # kg/m^3
BLOCK_MASS = 4.0             # kg
TOP = 0.5                    # m: the height of the top lead's end


def spring_rate() -> float:
    """The close-coiled spring's stiffness G d^4 / (8 D^3 n) (N/m)."""
    d = 2 * WIRE_RADIUS
    return SHEAR_MODULUS * d**4 / (8 * COIL_DIAMETER**3 * TURNS)


def static_load() -> float:
    """The weight the coil carries at its bottom (N): the block's, the bottom lead's and half the
    coil's own (a uniformly loaded spring stretches as under half its weight at its end)."""
    linear_density = DENSITY * math.pi * WIRE_RADIUS**2
    coil_length = TURNS * math.hypot(math.pi * COIL_DIAMETER, PITCH)
    return (BLOCK_MASS + linear_density * (COIL_DIAMETER / 2 + coil_length / 2)) * G


def spring_nodes() -> tuple[np.ndarray, np.ndarray]:
    """The wire's nodes (top lead, coil, bottom lead) and each element's frame axis."""
    R = COIL_DIAMETER / 2
    lead = np.linspace(0.0, 1.0, LEAD_NODES + 1)
    # the coil from angle 0 at the top down by PITCH per turn
    u = np.linspace(0.0, 1.0, TURNS * NODES_PER_TURN + 1)
    angle = 2 * math.pi * TURNS * u
    coil = np.stack([R * np.cos(angle), R * np.sin(angle), TOP - PITCH * TURNS * u], axis=1)
    top = np.stack([R * lead, np.zeros_like(lead), np.full_like(lead, TOP)], axis=1)
    end = coil[-1]
    bottom = np.stack([end[0] * (1 - lead), end[1] * (1 - lead), np.full_like(lead, end[2])], axis=1)
    nodes = np.concatenate([top, coil[1:], bottom[1:]])
    # frame axes: vertical on the leads, the coil's radial direction on the coil
    tangent = np.diff(nodes, axis=0)
    mid = 0.5 * (nodes[1:] + nodes[:-1])
    radial = np.stack([mid[:, 0], mid[:, 1], np.zeros(len(mid))], axis=1)
    on_lead = np.abs(tangent[:, 2]) < 1e-12
    radial[on_lead] = [0.0, 0.0, 1.0]
    return nodes, radial


def build(scene: sdp.Scene):
    """The spring, its anchor and the block; returns (spring, block)."""
    nodes, axes = spring_nodes()
    model = ex.generate_tubular_rod_model_data(nodes=nodes, element_frame_axes=axes, radius=WIRE_RADIUS,
                                               num_cross_section_segments=8, is_closed_loop=False)
    area = math.pi * WIRE_RADIUS**2
    polar = 0.5 * math.pi * WIRE_RADIUS**4
    material = ex.RodMaterialParams(linear_density=DENSITY * area, linear_rotational_inertia=DENSITY * polar,
                                    axial_stiffness=YOUNGS_MODULUS * area, torsional_stiffness=SHEAR_MODULUS * polar,
                                    flexural_stiffness=[YOUNGS_MODULUS * polar / 2] * 2, mass_damping_coefficient=5.0)
    spring = ex.create_rod_actor(scene, ex.RodActorParams(name="Spring", shape=sdp.create_model_shape(model), material=material))
    last_node, last_element = len(nodes) - 1, len(nodes) - 2
    # stiff ties: far stiffer than the spring (N/m) and than its wire's twist (N m/rad)
    k_pos, k_rot = 1e3 * YOUNGS_MODULUS * area, 1e3 * SHEAR_MODULUS * polar
    anchor = scene.create_rigid_actor(name="Anchor", shape=sdp.create_box_shape(half_extents=[0.01, 0.01, 0.01]), mass=1.0,
                                      is_static=True, world_from_local=sdp.TransformRT(translation=[0.0, 0.0, TOP + 0.01]))
    scene.create_deformable_node_position_constraint(actor=spring.get_handle(), node_index=0, position=list(nodes[0]), stiffness=k_pos)
    scene.create_rod_element_rotation_to_rigid_constraint(rigid_actor=anchor.get_handle(), rod_actor=spring.get_handle(), element_index=0,
                                                          stiffness=k_rot)
    half = 0.02
    block = scene.create_rigid_actor(name="Block", shape=sdp.create_box_shape(half_extents=[half, half, half]), mass=BLOCK_MASS,
                                     world_from_local=sdp.TransformRT(translation=list(nodes[-1] - [0.0, 0.0, half])))
    scene.create_deformable_node_to_rigid_constraint(deformable_actor=spring.get_handle(), rigid_actor=block.get_handle(),
                                                     deformable_node_index=last_node, fix_to_deformable_pos=True, stiffness=k_pos)
    scene.create_rod_element_rotation_to_rigid_constraint(rigid_actor=block.get_handle(), rod_actor=spring.get_handle(),
                                                          element_index=last_element, stiffness=k_rot)
    return spring, block


def run(seconds: float = 2.0, dt: float = 0.005, debugger: bool = False) -> dict:
    """Lets the block settle; returns its drop (m), the expected drop m g / k and the drop over time."""
    sdp.initialize(num_worker_threads=0)
    scene = sdp.create_scene("Rod spring")
    scene.set_gravity([0, 0, -G])
    _, block = build(scene)
    if debugger:
        sdp.debugger.attach()
    z0 = float(block.get_root_transform().translation[2])
    drops = []
    for _ in range(int(round(seconds / dt))):
        scene.step(dt)
        drops.append(z0 - float(block.get_root_transform().translation[2]))
    if debugger:
        sdp.debugger.detach()
    sdp.shutdown()
    return {"drop": drops[-1], "expected": static_load() / spring_rate(), "drops": drops}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=2.0)
    parser.add_argument("--dt", type=float, default=0.005)
    parser.add_argument("--debugger", action="store_true", help="stream the run to the scene debugger")
    args = parser.parse_args()
    result = run(args.seconds, args.dt, args.debugger)
    print(f"spring rate G d^4 / (8 D^3 n): {spring_rate():.1f} N/m")
    print(f"expected drop (load / rate):   {1000 * result['expected']:.2f} mm")
    print(f"simulated drop:                {1000 * result['drop']:.2f} mm")


if __name__ == "__main__":
    main()
