"""A straight cylindrical bundle along x (FiberBundleSource Shape=Cylinder), solved, as tubes.

    pvbatch Examples/bundle_cylinder.py <path to FiberPLI.so> <output folder>
"""
import passive_openmp  # noqa: F401  (first: restarts once with OMP_WAIT_POLICY=PASSIVE when unset)
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bundle_common import run  # noqa: E402

run("cylinder", ([-40, 45, 60], [0, 0, 0], [0, 1, 0]),
    Shape="Cylinder", BundleRadius=10.0, Length=60.0, FiberRadius=0.8, RadiusSpread=0.1,
    RadiusDistribution="LogNormal", FiberSpacing=2.0, NumberOfFibers=0, SegmentLength=2.0,
    Displacement=0.2, CrossingAngle=90.0, UncrossedFraction=0.25, RanvierSpacing=0.0,
    RanvierDepth=0.3, RanvierLength=1.0, Seed=42)
