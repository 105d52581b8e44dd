#pragma once
// The Actor class is bound in parts, one file per area of its API.

#include "bind_common.h"

namespace superdex::python {

using ActorClass = nb::class_<Actor>;

// bind_actor_queries.cpp: queries and the results they give (ContactPoint, NodeContactForce,
// SdfDistances), contact forces.
void export_query_results(nb::module_& m);
void add_query_methods(ActorClass& c);
// bind_actor_soft.cpp: node displacements, positions and velocities, materials, recentering,
// boundary conditions.
void add_soft_methods(ActorClass& c);
// bind_actor_articulated.cpp: poses, link transforms, joint velocities, Jacobians, dynamics
// terms, joint parameters and drives.
void add_articulated_methods(ActorClass& c);
// bind_pose_controller.cpp: the pose controller's params and info types, and its methods.
void export_pose_controller(nb::module_& m);
void add_pose_controller_methods(ActorClass& c);

}  // namespace superdex::python
