"""Writes the CATERPillar configurations of the side-by-side run (bench/caterpillar/README.md):
    /usr/bin/python3 bench/caterpillar/configs.py OUTDIR
One JSON per case in OUTDIR (cfg_<case>.json, results into OUTDIR/out_<case>/): a (40 µm)³ voxel,
2 threads, CATERPillar's recommended realism (Gamma α 4, β 0.25 µm, beading amplitude 0.3,
overlapping factor 4, tortuosity ε 0.4), the density targets of realistic_bench.py's cases, and the
corpus-callosum case again at ε 0.15, whose tortuosity is closer to the corpus callosum's."""
import json
import os
import sys

out = os.path.abspath(sys.argv[1])
CASES = {  # name: (populations, ICVF %, ε)
    "cc": (1, 80.0, 0.4),
    "cc-eps0.15": (1, 80.0, 0.15),
    "crossing": (2, 65.0, 0.4),
    "three": (3, 55.0, 0.4),
}
for name, (populations, icvf, epsilon) in CASES.items():
    config = {
        "GeneralParameters": {"OutputDirectory": os.path.join(out, "out_" + name) + "/", "Filename": name,
                              "VoxelEdgeLength": 40.0, "Repetitions": 1, "OverlappingFactor": 4},
        "AxonParameters": {"AxonsICVF": icvf, "AxonsWithMyelinICVF": 0.0, "BloodVesselsICVF": 0.0,
                           "NumberOfPopulations": populations, "CrossingFibersType": 1, "NumberOfThreads": 2,
                           "Alpha": 4.0, "Beta": 0.25, "MinRadius": 0.15, "Tortuosity_Epsilon": epsilon,
                           "FODF_c2": 1.0, "BeadingAmplitude": 0.3, "BeadingStd": 0.02,
                           "K1": 0.35, "K2": 0.006, "K3": 0.024, "Tortuous": True, "CanShrink": True,
                           "RegrowThreshold": 10, "OndulationFactor": 5},
        "GlialParameters": {"Pop1SomaICVF": 0.0, "Pop1ProcessesICVF": 0.0, "Pop1SomaRadiusMean": 6.0,
                            "Pop1SomaRadiusStd": 0.5, "Pop1MeanProcessLength": 15.0, "Pop1StdProcessLength": 2.0,
                            "Pop1NbrPrimaryProcesses": 4, "Pop1Branching": True,
                            "Pop2SomaICVF": 0.0, "Pop2ProcessesICVF": 0.0, "Pop2SomaRadiusMean": 4.0,
                            "Pop2SomaRadiusStd": 0.3, "Pop2MeanProcessLength": 10.0, "Pop2StdProcessLength": 1.5,
                            "Pop2NbrPrimaryProcesses": 3, "Pop2Branching": False},
    }
    with open(os.path.join(out, "cfg_%s.json" % name), "w") as f:
        json.dump(config, f, indent=1)
    print(os.path.join(out, "cfg_%s.json" % name))
