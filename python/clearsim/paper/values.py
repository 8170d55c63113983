"""The numbers the seed paper reports in its section 5 (text of §5.1–§5.2; the figures' data are
not available), keyed by the study's case keys (see :mod:`clearsim.paper.cases`).

Units: peaks in m, m/s, m/s² at times in s; reliability minima at crank angles in degrees (the
start of the paper's 18° bin), with the reliability index β and R = Φ(β). ``None`` where the
paper gives no value.
"""

from __future__ import annotations

from typing import Dict, List, Optional, Tuple

#: Error peaks ``{case: {quantity: (signed peak value, time [s])}}`` (paper §5.1, §5.2).
PEAKS: Dict[str, Dict[str, Tuple[float, float]]] = {
    "dry-c0.3-5pi": {"displacement": (5.601e-4, 0.207), "velocity": (0.282, 0.295), "acceleration": (-345.3, 0.154)},
    "dry-c0.5-5pi": {"displacement": (9.714e-4, 0.207), "velocity": (0.358, 0.111), "acceleration": (1537.0, 0.120)},
    "lub-c0.3-5pi": {"displacement": (8.677e-4, 0.220), "velocity": (0.013, 0.152), "acceleration": (-0.881, 0.273)},
    "lub-c0.5-5pi": {"displacement": (4.399e-4, 0.220), "velocity": (0.056, 0.152), "acceleration": (-6.074, 0.273)},
    "dry-c0.6-5pi": {"displacement": (1.106e-3, 0.214), "velocity": (0.289, 0.083), "acceleration": (1104.0, 0.091)},
    "lub-c0.6-5pi": {"displacement": (1.059e-3, 0.214), "velocity": (0.081, 0.280), "acceleration": (-7.32, 0.155)},
    "dry-c0.6-8pi": {"displacement": (1.123e-3, 0.141), "velocity": (-0.364, 0.179), "acceleration": (1163.0, 0.200)},
    "lub-c0.6-8pi": {"displacement": (1.072e-3, 0.141), "velocity": (-0.196, 0.083), "acceleration": (-39.94, 0.091)},
}

#: Minimum reliability ``{case: {quantity: (angle [deg], β or None, R)}}`` within one cycle
#: (for the clearance study's displacement: the first of the three cycles).
MINIMA: Dict[str, Dict[str, Tuple[float, Optional[float], float]]] = {
    "dry-c0.3-5pi": {"displacement": (198.0, None, 0.9842), "velocity": (270.0, 2.282, 0.9887), "acceleration": (270.0, 0.484, 0.6861)},
    "dry-c0.5-5pi": {"displacement": (198.0, None, 0.9468), "velocity": (90.0, 1.412, 0.9210), "acceleration": (90.0, -0.098, 0.4611)},
    "lub-c0.3-5pi": {"displacement": (216.0, None, 0.9898), "velocity": (270.0, 2.864, 0.9980), "acceleration": (144.0, 2.984, 0.9983)},
    "lub-c0.5-5pi": {"displacement": (216.0, None, 0.9557), "velocity": (270.0, 2.419, 0.9922), "acceleration": (144.0, 2.823, 0.9978)},
    "dry-c0.6-5pi": {"displacement": (198.0, 1.358, 0.9127), "velocity": (90.0, 1.412, 0.9210), "acceleration": (90.0, -0.098, 0.4611)},
    "dry-c0.6-8pi": {"displacement": (216.0, 1.325, 0.9074), "velocity": (270.0, 1.027, 0.8471), "acceleration": (180.0, -0.6811, 0.2480)},
    "lub-c0.6-5pi": {"displacement": (198.0, 1.431, 0.9226), "velocity": (144.0, 2.434, 0.9926), "acceleration": (144.0, 2.834, 0.9977)},
    # printed as "5π" in the paper (a typo: it is the second lubricated case, 8π)
    "lub-c0.6-8pi": {"displacement": (216.0, 1.398, 0.9190), "velocity": (270.0, 1.635, 0.9489), "acceleration": (270.0, 2.151, 0.9842)},
}

#: Displacement reliability minima of each of the three cycles (Fig. 11a): ``[(angle, R), …]``.
DISPLACEMENT_CYCLE_MINIMA: Dict[str, List[Tuple[float, float]]] = {
    "dry-c0.3-5pi": [(198.0, 0.9842), (558.0, 0.9843), (918.0, 0.9843)],
    "lub-c0.3-5pi": [(216.0, 0.9898), (576.0, 0.9901), (936.0, 0.9901)],
    "dry-c0.5-5pi": [(198.0, 0.9468), (558.0, 0.9470), (918.0, 0.9468)],
    "lub-c0.5-5pi": [(216.0, 0.9557), (558.0, 0.9563), (918.0, 0.9563)],
}

__all__ = ["PEAKS", "MINIMA", "DISPLACEMENT_CYCLE_MINIMA"]
