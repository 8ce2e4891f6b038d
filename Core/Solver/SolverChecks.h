/// SolverChecks: what the collision solver refuses before it changes the model (docs/solver.md
/// §8, §9): the input piece, the memory the points can take, stacks of identical fibers and gaps
/// that make every link collide. Each returns "" or a message naming the option, fiber or size
/// and its value.
#pragma once

#include "Model/FiberModel.h"
#include "Solver/CollisionSolver.h"

#include <cstdint>
#include <string>
#include <vector>

namespace fiberpli
{

class SolverEngine;

/// validateModel (short fibers allowed: they are copied through), the fiber named by its global
/// index (global[i] of piece fiber i; none given: the piece index), so a distributed run's message
/// is the serial one for any rank count.
std::string validatePiece(const FiberModel& piece, const std::vector<std::int64_t>& global);

/// Splitting makes up to (arc length / l_min) points per fiber: refuse sizes beyond the memory
/// budget before any allocation. Distributed: the fibers this rank owns, against its budget.
std::string checkMemory(const SolverEngine& s);

/// Exact copies of a fiber beyond a few, and a MinimumGap beyond a few radii: both would make the
/// colliding pairs grow with the square of the copies or the gap. comm: the largest radius of all
/// ranks.
std::string checkStacksAndGap(const FiberModel& model, const CollisionSolverOptions& o, Comm* comm);

} // namespace fiberpli
