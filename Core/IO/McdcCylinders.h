/// McdcCylinders: the cylinder obstacle lists of the MC/DC diffusion simulator
/// (docs/diffusion-export.md §4; the layout MC/DC's obstacle loader reads):
///   line 1: the scale that turns the file's numbers into MC/DC's millimetres (FiberPLI writes
///           0.001: the numbers are µm);
///   `cylinders_list`: one cylinder a line `x y z r`, axis parallel to z through (x, y, z);
///   `oriented_cylinders_list`: one cylinder a line `x y z ox oy oz r`, axis through the two
///           points (x, y, z) and (ox, oy, oz) — FiberPLI writes a fiber's first and last point.
/// Fields are separated by single spaces (MC/DC tells the two kinds apart by counting them).
/// A cylinder has one radius: the fiber's largest (its capsules lie inside that cylinder).
/// Only straight fibers can be written: a fiber whose points leave the line through its first and
/// last point (for `cylinders_list`: the z-parallel line through its first point) by more than the
/// tolerance is refused, naming the worst fiber.
#pragma once

#include "Model/FiberModel.h"

#include <ostream>
#include <string>

namespace fiberpli
{

enum class McdcCylinderList
{
  ZAligned, ///< cylinders_list
  Oriented  ///< oriented_cylinders_list
};

/// Default straightness tolerance (µm).
constexpr double kMcdcDefaultStraightness = 0.01;

/// Largest distance (µm) of a point of the fiber from its axis (see above).
double mcdcAxisDeviation(const Fiber& fiber, McdcCylinderList kind);

/// Writes the list. Returns "" on success, else the reason: invalid model, tolerance not finite or
/// < 0, or "fiber <index> (id <id>) deviates <d> µm from ..." for the fiber that deviates most
/// (nothing is written then), or a stream failure. Use AtomicFile to protect the target file.
std::string writeMcdcCylinders(std::ostream& out, const FiberModel& model, McdcCylinderList kind,
  double tolerance = kMcdcDefaultStraightness);

} // namespace fiberpli
