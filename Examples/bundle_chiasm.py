"""The paper's chiasm-like model: two nerves crossing at 90 degrees, a quarter of each nerve's
fibers (the lateral ones) turning back to its own side, nodes of Ranvier every 20 um
(FiberBundleSource Shape=Chiasm), solved.

    pvbatch Examples/bundle_chiasm.py <path to FiberPLI.so> <output folder>
"""
import passive_openmp  # noqa: F401  (first: restarts once with OMP_WAIT_POLICY=PASSIVE when unset)
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bundle_common import run  # noqa: E402

run("chiasm", ([0, 0, 100], [0, 0, 0], [0, 1, 0]),
    Shape="Chiasm", BundleRadius=10.0, Length=60.0, FiberRadius=0.8, RadiusSpread=0.0,
    RadiusDistribution="LogNormal", FiberSpacing=2.0, NumberOfFibers=0, SegmentLength=2.0,
    Displacement=0.2, CrossingAngle=90.0, UncrossedFraction=0.25, RanvierSpacing=20.0,
    RanvierDepth=0.3, RanvierLength=1.0, Seed=42)
