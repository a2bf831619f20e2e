"""thud — design single-unit impact dampers from Python, on the engine of the `thud` app.

pulse(**params) -> Pulse, simulate(**params) -> Run (an Ensemble with ensemble=N > 1),
simulate_ensemble(runs, **params) -> Ensemble, sweep(masses_kg, gaps_m, **params) -> Chart,
response(freqs_hz, **params) -> Response. Every result pickles; tables with pandas/xarray.

Parameters are the command line's long flags as keywords (``--main-mass`` → ``main_mass=``).
A plain number is in SI units (kg, m, s, m/s, N/m, N·s/m, N/m^1.5, kg/m³, Pa·s/m) except angles
(degrees), levels (dB) and inclinations (cm/s); a string may carry a unit: "40.5g", "19.05mm",
"4cm", "250ms", "45deg". ``None`` means "not given". Every value is checked against the same
range table as the command line (``thud.ranges()``); bad input raises ``ParameterError`` (a
``ValueError``) with the command line's one-line message, the parameter spelled as typed.

The GIL is released while the engine runs: Python threads run designs in parallel. Results are
bit-for-bit those of ``thud pulse|simulate|sweep|response --json`` for the same design.
"""

import os
from typing import Any, Callable, Dict, List, Literal, Optional, Sequence, Tuple, TypedDict, Union, overload

import numpy as np
import numpy.typing as npt

__version__: str

#: A number in the parameter's plain unit, or a string with a unit ("40.5g").
Quantity = Union[float, str]
#: A whole number (or its text, "1e4").
Count = Union[int, str]
Source = Literal["single", "dipole", "quadrupole"]
QuadSigns = Literal["paper", "rigid"]
PulseShape = Literal["half-sine", "hertz"]
Model = Literal["paper", "physical"]
Solver = Literal["event", "newmark"]
FloatArray = npt.NDArray[np.float64]
#: An ensemble of N > 1 runs (the range of ensemble=): simulate() then returns an Ensemble.
EnsembleSize = Literal[
    2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 24, 25, 26, 27,
    28, 29, 30, 31, 32, 33, 34, 35, 36, 37, 38, 39, 40, 41, 42, 43, 44, 45, 46, 47, 48, 49, 50, 51,
    52, 53, 54, 55, 56, 57, 58, 59, 60, 61, 62, 63, 64, 65, 66, 67, 68, 69, 70, 71, 72, 73, 74, 75,
    76, 77, 78, 79, 80, 81, 82, 83, 84, 85, 86, 87, 88, 89, 90, 91, 92, 93, 94, 95, 96, 97, 98, 99,
    100, 101, 102, 103, 104, 105, 106, 107, 108, 109, 110, 111, 112, 113, 114, 115, 116, 117, 118,
    119, 120, 121, 122, 123, 124, 125, 126, 127, 128, 129, 130, 131, 132, 133, 134, 135, 136, 137,
    138, 139, 140, 141, 142, 143, 144, 145, 146, 147, 148, 149, 150, 151, 152, 153, 154, 155, 156,
    157, 158, 159, 160, 161, 162, 163, 164, 165, 166, 167, 168, 169, 170, 171, 172, 173, 174, 175,
    176, 177, 178, 179, 180, 181, 182, 183, 184, 185, 186, 187, 188, 189, 190, 191, 192, 193, 194,
    195, 196, 197, 198, 199, 200, 201, 202, 203, 204, 205, 206, 207, 208, 209, 210, 211, 212, 213,
    214, 215, 216, 217, 218, 219, 220, 221, 222, 223, 224, 225, 226, 227, 228, 229, 230, 231, 232,
    233, 234, 235, 236, 237, 238, 239, 240, 241, 242, 243, 244, 245, 246, 247, 248, 249, 250, 251,
    252, 253, 254, 255, 256, 257, 258, 259, 260, 261, 262, 263, 264, 265, 266, 267, 268, 269, 270,
    271, 272, 273, 274, 275, 276, 277, 278, 279, 280, 281, 282, 283, 284, 285, 286, 287, 288, 289,
    290, 291, 292, 293, 294, 295, 296, 297, 298, 299, 300, 301, 302, 303, 304, 305, 306, 307, 308,
    309, 310, 311, 312, 313, 314, 315, 316, 317, 318, 319, 320, 321, 322, 323, 324, 325, 326, 327,
    328, 329, 330, 331, 332, 333, 334, 335, 336, 337, 338, 339, 340, 341, 342, 343, 344, 345, 346,
    347, 348, 349, 350, 351, 352, 353, 354, 355, 356, 357, 358, 359, 360, 361, 362, 363, 364, 365,
    366, 367, 368, 369, 370, 371, 372, 373, 374, 375, 376, 377, 378, 379, 380, 381, 382, 383, 384,
    385, 386, 387, 388, 389, 390, 391, 392, 393, 394, 395, 396, 397, 398, 399, 400, 401, 402, 403,
    404, 405, 406, 407, 408, 409, 410, 411, 412, 413, 414, 415, 416, 417, 418, 419, 420, 421, 422,
    423, 424, 425, 426, 427, 428, 429, 430, 431, 432, 433, 434, 435, 436, 437, 438, 439, 440, 441,
    442, 443, 444, 445, 446, 447, 448, 449, 450, 451, 452, 453, 454, 455, 456, 457, 458, 459, 460,
    461, 462, 463, 464, 465, 466, 467, 468, 469, 470, 471, 472, 473, 474, 475, 476, 477, 478, 479,
    480, 481, 482, 483, 484, 485, 486, 487, 488, 489, 490, 491, 492, 493, 494, 495, 496, 497, 498,
    499, 500, 501, 502, 503, 504, 505, 506, 507, 508, 509, 510, 511, 512, 513, 514, 515, 516, 517,
    518, 519, 520, 521, 522, 523, 524, 525, 526, 527, 528, 529, 530, 531, 532, 533, 534, 535, 536,
    537, 538, 539, 540, 541, 542, 543, 544, 545, 546, 547, 548, 549, 550, 551, 552, 553, 554, 555,
    556, 557, 558, 559, 560, 561, 562, 563, 564, 565, 566, 567, 568, 569, 570, 571, 572, 573, 574,
    575, 576, 577, 578, 579, 580, 581, 582, 583, 584, 585, 586, 587, 588, 589, 590, 591, 592, 593,
    594, 595, 596, 597, 598, 599, 600, 601, 602, 603, 604, 605, 606, 607, 608, 609, 610, 611, 612,
    613, 614, 615, 616, 617, 618, 619, 620, 621, 622, 623, 624, 625, 626, 627, 628, 629, 630, 631,
    632, 633, 634, 635, 636, 637, 638, 639, 640, 641, 642, 643, 644, 645, 646, 647, 648, 649, 650,
    651, 652, 653, 654, 655, 656, 657, 658, 659, 660, 661, 662, 663, 664, 665, 666, 667, 668, 669,
    670, 671, 672, 673, 674, 675, 676, 677, 678, 679, 680, 681, 682, 683, 684, 685, 686, 687, 688,
    689, 690, 691, 692, 693, 694, 695, 696, 697, 698, 699, 700, 701, 702, 703, 704, 705, 706, 707,
    708, 709, 710, 711, 712, 713, 714, 715, 716, 717, 718, 719, 720, 721, 722, 723, 724, 725, 726,
    727, 728, 729, 730, 731, 732, 733, 734, 735, 736, 737, 738, 739, 740, 741, 742, 743, 744, 745,
    746, 747, 748, 749, 750, 751, 752, 753, 754, 755, 756, 757, 758, 759, 760, 761, 762, 763, 764,
    765, 766, 767, 768, 769, 770, 771, 772, 773, 774, 775, 776, 777, 778, 779, 780, 781, 782, 783,
    784, 785, 786, 787, 788, 789, 790, 791, 792, 793, 794, 795, 796, 797, 798, 799, 800, 801, 802,
    803, 804, 805, 806, 807, 808, 809, 810, 811, 812, 813, 814, 815, 816, 817, 818, 819, 820, 821,
    822, 823, 824, 825, 826, 827, 828, 829, 830, 831, 832, 833, 834, 835, 836, 837, 838, 839, 840,
    841, 842, 843, 844, 845, 846, 847, 848, 849, 850, 851, 852, 853, 854, 855, 856, 857, 858, 859,
    860, 861, 862, 863, 864, 865, 866, 867, 868, 869, 870, 871, 872, 873, 874, 875, 876, 877, 878,
    879, 880, 881, 882, 883, 884, 885, 886, 887, 888, 889, 890, 891, 892, 893, 894, 895, 896, 897,
    898, 899, 900, 901, 902, 903, 904, 905, 906, 907, 908, 909, 910, 911, 912, 913, 914, 915, 916,
    917, 918, 919, 920, 921, 922, 923, 924, 925, 926, 927, 928, 929, 930, 931, 932, 933, 934, 935,
    936, 937, 938, 939, 940, 941, 942, 943, 944, 945, 946, 947, 948, 949, 950, 951, 952, 953, 954,
    955, 956, 957, 958, 959, 960, 961, 962, 963, 964, 965, 966, 967, 968, 969, 970, 971, 972, 973,
    974, 975, 976, 977, 978, 979, 980, 981, 982, 983, 984, 985, 986, 987, 988, 989, 990, 991, 992,
    993, 994, 995, 996, 997, 998, 999, 1000
]
#: progress=: True for a bar on stderr (tqdm if installed), or a callable progress(done, total).
ProgressArg = Union[bool, Callable[[int, int], object], None]

class ParameterError(ValueError):
    """A parameter thud cannot accept: unknown, of the wrong type, NaN/inf, out of its range,
    or a run whose work is over its cap. ``str(e)`` is one line naming the parameter, e.g.
    "invalid main_mass: 1e308 kg is out of range; the main mass M must be 0.001 to 1e6 kg"."""

    #: The parameter's name as typed (``main_mass``), or the option (``preset``, ``points``).
    param: str

class Pulse:
    """One Hertzian impact heard at one observer: the inputs as used, the contact (Eqs 5–7),
    the levels (dB re 20 µPa) and the waveform. The fields of ``thud pulse --json``."""

    radius_m: float
    """Sphere radius a (m)."""
    mass_kg: float
    """Sphere mass m (kg)."""
    u0_m_s: float
    """Impact speed U0 (m/s)."""
    k_hz_n_m1_5: float
    """Hertz stiffness K_HZ (N/m^1.5)."""
    r_m: float
    """Observer distance r (m)."""
    theta_deg: float
    """Observer angle θ from the plate's normal (degrees)."""
    source: Source
    quad_signs: QuadSigns
    pulse: PulseShape
    rho_c_pa_s_m: float
    """Air impedance ρ0·c (Pa·s/m)."""
    c_m_s: float
    """Speed of sound c (m/s)."""
    alpha_max_m: float
    """Peak approach α_max (m)."""
    accel_max_m_s2: float
    """Peak acceleration A_max (m/s²)."""
    tau_s: float
    """Contact duration τ (s)."""
    force_max_n: float
    """Peak contact force (N)."""
    arrival_s: float
    """Arrival of the direct wave (s after the contact starts)."""
    spl_db: float
    """SPL (dB): rms pressure over one contact duration from the direct arrival."""
    spl_definition: str
    spl_peak_db: float
    """Peak level 20·log10(max|p|/20 µPa) (dB)."""
    sel_db: float
    """Sound exposure level (dB)."""
    p_rms_pa: float
    """rms pressure over the SPL window (Pa)."""
    p_max_pa: float
    """Largest pressure (Pa)."""
    p_min_pa: float
    """Smallest pressure (Pa)."""
    extrema: Dict[str, FloatArray]
    """Local extrema of the waveform: {"t_s": times (s), "p_pa": pressures (Pa)}."""
    t_s: FloatArray
    """Waveform times (s) from the contact's start."""
    p_pa: FloatArray
    """Waveform pressure (Pa)."""
    def to_dataframe(self) -> Any:
        """The waveform as a pandas.DataFrame: t_s (s), p_pa (Pa); the scalars in .attrs."""
    def to_xarray(self) -> Any:
        """The waveform as an xarray.Dataset on t_s (s): p_pa (Pa); the scalars in attrs."""
    def as_dict(self, json: bool = False) -> Dict[str, Any]:
        """Every field in one dict; json=True: plain lists, numbers and None (NaN → None)."""
    def _repr_html_(self) -> str: ...
    def _file(self, kind: str, size: Optional[Tuple[float, float]] = None, title: bool = True,
              full_scale: float = 20.0, format: str = "pcm16") -> bytes: ...
    def to_svg(self, path: Union[str, "os.PathLike[str]"], *, overwrite: bool = False, size: Optional[Tuple[float, float]] = None, title: bool = True) -> None:
        """The pressure against time after the direct arrival as SVG, the bytes of ``thud export
        svg pulse`` (same flags, ``--points`` the pulse's samples); an existing file is kept unless overwrite."""
    def to_pdf(self, path: Union[str, "os.PathLike[str]"], *, overwrite: bool = False, size: Optional[Tuple[float, float]] = None, title: bool = True) -> None:
        """The pulse as a one-page PDF (``thud export pdf pulse``)."""
    def to_wav(self, path: Union[str, "os.PathLike[str]"], *, overwrite: bool = False, full_scale: float = 20.0,
               format: Literal["pcm16", "pcm24", "float"] = "pcm16") -> None:
        """The pulse's sound (``thud export wav pulse``): 48 kHz mono from the contact's start to
        0.1 s after the last wave, sample = mean pressure over its interval / full_scale Pa."""

class Run:
    """One damper design run through its impacts: the fields of ``thud simulate --json`` and
    the time history. None = no such value (too few maxima for e, no impact for SPLmax)."""

    design: Dict[str, object]
    """The design as run (the JSON "design" object; SI units, angles in degrees)."""
    ball_radius_m: float
    """Ball radius (m)."""
    n_impacts: int
    inclination_cm_s: Optional[float]
    """Damping inclination e of Eq 27 from the first two cycle maxima (cm/s)."""
    inclination_fit_cm_s: Optional[float]
    """Robust least-squares inclination e_fit (cm/s)."""
    u0_max_m_s: float
    """U0max: the largest contact speed by the design's rule (m/s)."""
    zdot_abs_max_m_s: float
    """Largest |z'| over the run including t = 0 (m/s)."""
    spl_max_db: Optional[float]
    """SPLmax: the SPL of an impact at U0max (dB)."""
    contact_duration_s: Optional[float]
    """Contact duration at U0max (s)."""
    restitution_mean: Optional[float]
    """Mean restitution u_out/u_in."""
    zone: Optional[int]
    """Zone 1 noisy & weak, 2 noisy & strong, 3 quiet & strong (the target), 4 quiet & weak."""
    impacts: Dict[str, np.ndarray]
    """Every impact, as arrays: t_s (s), wall (±1, int8), u_in_m_s, u_out_m_s (m/s),
    restitution, t_end_s, duration_s (s), penetration_max_m (m), spl_db (dB)."""
    maxima: Dict[str, FloatArray]
    """Cycle maxima of the main mass: t_s (s), x_m (m)."""
    energy: Dict[str, float]
    """Energy ledger (J): initial_j, final_mechanical_j, dissipated_viscous_j, dissipated_contact_j."""
    final_time_s: float
    """Time reached (s)."""
    truncated: bool
    """Whether the solver's work cap stopped the run before its duration."""
    truncation_reason: Optional[str]
    steady: Optional[Dict[str, object]]
    """The steady state of a forced run over its last ``periods`` forcing periods (the JSON
    "steady" object): amplitude_m and amplitude_linear_m (m; without the ball, closed form),
    reduction_db and leq_db (dB), impacts_per_period, periodic, settled, truncated, the
    window (s). None without a force."""
    history: Dict[str, FloatArray]
    """Uniform time history: t_s (s), x_m (main mass, m), y_m (ball, m), x_free_m (no damper, m)."""
    def impacts_frame(self) -> Any:
        """Every impact as a row of a pandas.DataFrame, t_s first (units in the names)."""
    def history_frame(self) -> Any:
        """The time history as a pandas.DataFrame: t_s, x_m, y_m, x_free_m."""
    def to_xarray(self) -> Any:
        """The time history as an xarray.Dataset on t_s (s): x_m, y_m, x_free_m (m)."""
    def as_dict(self, json: bool = False) -> Dict[str, Any]:
        """Every field in one dict; json=True: plain lists, numbers and None (NaN → None)."""
    def _repr_html_(self) -> str: ...
    def to_svg(self, path: Union[str, "os.PathLike[str]"], *, overwrite: bool = False, size: Optional[Tuple[float, float]] = None, title: bool = True) -> None:
        """The time history as SVG, the bytes of ``thud export svg history`` (``--points`` the
        run's samples); an existing file is kept unless overwrite."""
    def to_pdf(self, path: Union[str, "os.PathLike[str]"], *, overwrite: bool = False, size: Optional[Tuple[float, float]] = None, title: bool = True) -> None:
        """The time history as a one-page PDF (``thud export pdf history``)."""
    def to_wav(self, path: Union[str, "os.PathLike[str]"], *, overwrite: bool = False, full_scale: float = 20.0,
               format: Literal["pcm16", "pcm24", "float"] = "pcm16") -> None:
        """The damper's sound over the run (``thud export wav``): 48 kHz mono, sample = mean
        pressure over its interval / full_scale Pa."""

class Chart:
    """The design chart of a sweep. Every metric is a 2-D array of shape
    (len(gaps_m), len(masses_kg)): row = gap, column = mass. NaN = no such value (no impact,
    so no SPLmax; too few maxima for e); zone 0 = no zone. The cells of ``thud sweep --json``."""

    design: Dict[str, object]
    masses_kg: FloatArray
    """Impact masses, the columns (kg)."""
    gaps_m: FloatArray
    """Gaps, the rows (m)."""
    n_impacts: npt.NDArray[np.int64]
    inclination_cm_s: FloatArray
    """e of Eq 27 (cm/s)."""
    inclination_fit_cm_s: FloatArray
    """e_fit (cm/s)."""
    u0_max_m_s: FloatArray
    """U0max (m/s)."""
    zdot_abs_max_m_s: FloatArray
    spl_max_db: FloatArray
    """SPLmax (dB)."""
    contact_duration_s: FloatArray
    restitution_mean: FloatArray
    zone: npt.NDArray[np.int8]
    """Zone 1–4; 0 = none."""
    thresholds: Dict[str, object]
    """{"spl_db": L* (dB), "inclination_cm_s": e* (cm/s), "zone_by": "paper" | "fit"}."""
    runs: int
    """Runs per cell N (1: the single trajectory; with more the metrics are the medians)."""
    zone3_probability: Optional[FloatArray]
    """Fraction of each cell's runs in zone 3 (None without an ensemble)."""
    agreement: Optional[FloatArray]
    """Fraction of each cell's runs in the zone of its medians (None without an ensemble)."""
    spread: Optional[Dict[str, Dict[str, FloatArray]]]
    """{metric: {"p10", "median", "p90"}} of e, e_fit (cm/s), U0max (m/s), SPLmax (dB), each
    2-D (None without an ensemble)."""
    ensemble: Optional[Dict[str, np.ndarray]]
    """Every run of every cell as 3-D arrays (gap, mass, run): ball_position_m (m), the metrics,
    zone (int8, 0 = none) (None without an ensemble)."""
    def to_dataframe(self) -> Any:
        """A tidy pandas.DataFrame, one row per cell, the columns of `thud sweep --csv`
        (schema()["sweep"]: mass_kg, gap_m, the metrics); with an ensemble those of `thud sweep
        --ensemble N --csv` (schema()["sweep_ensemble"]: mass_kg, gap_m, runs, the medians,
        X_p10 / X_median / X_p90, zone3_probability, agreement)."""
    def _ensemble_figure(self, pdf: bool = False, size: Optional[Tuple[float, float]] = None,
                         title: bool = True) -> bytes: ...
    def runs_frame(self) -> Any:
        """A chart of ensembles, one row per run of each cell (run, mass_kg, gap_m, ball_position_m, metrics)."""
    def to_xarray(self) -> Any:
        """An xarray.Dataset on gap_m × mass_kg (× run with an ensemble), units in attrs."""
    def table5(self, band_cm_s: float = 0.2, no_limit: bool = False) -> Dict[str, np.ndarray]:
        """Table 5: the SPLmax spread per band of e of width band_cm_s (cm/s), as
        ``thud sweep --band``: e_lo_cm_s, e_hi_cm_s (cm/s), count, spl_min_db, spl_max_db (dB)."""
    def as_dict(self, json: bool = False) -> Dict[str, Any]:
        """Every field in one dict; json=True: plain lists, numbers and None (NaN → None)."""
    def _repr_html_(self) -> str: ...
    def to_svg(self, path: Union[str, "os.PathLike[str]"], *, figure: Literal["chart", "fig17"] = "chart",
               overwrite: bool = False, size: Optional[Tuple[float, float]] = None, title: bool = True) -> None:
        """The design chart (or Fig 17) as SVG, the bytes of ``thud export svg chart|fig17`` over
        this chart's masses and gaps; with ensemble=N the ensemble chart of ``thud sweep
        --ensemble N --svg``."""
    def to_pdf(self, path: Union[str, "os.PathLike[str]"], *, figure: Literal["chart", "fig17"] = "chart",
               overwrite: bool = False, size: Optional[Tuple[float, float]] = None, title: bool = True) -> None:
        """The design chart (or Fig 17) as a one-page PDF (``thud export pdf chart|fig17``)."""

class Ensemble:
    """One design from N ball offsets y0 = −d/2 + (k + ½)·d/N at rest (``simulate(ensemble=N)``):
    the fields of ``thud simulate --ensemble N --json``."""

    design: Dict[str, object]
    ball_radius_m: float
    """Ball radius (m)."""
    runs: int
    """Runs N."""
    zone: Optional[int]
    """The zone of the medians, 1–4."""
    zone3_probability: float
    """Fraction of the runs in zone 3."""
    agreement: float
    """Fraction of the runs in the zone of the medians."""
    spread: Dict[str, Dict[str, Optional[float]]]
    """{"inclination_cm_s" | "inclination_fit_cm_s" (cm/s) | "u0_max_m_s" (m/s) | "spl_max_db"
    (dB): {"p10", "median", "p90"}}, by nearest rank (None: among runs without the value)."""
    ensemble: Dict[str, np.ndarray]
    """Every run in order of k: ball_position_m (m), n_impacts, u0_max_m_s, zdot_abs_max_m_s
    (m/s), spl_max_db (dB), contact_duration_s (s), restitution_mean, inclination_cm_s,
    inclination_fit_cm_s (cm/s), zone (int8, 0 = none)."""
    truncated: bool
    """Whether any run stopped at a solver work cap."""
    truncation_reason: Optional[str]
    def to_dataframe(self) -> Any:
        """One row per run as a pandas.DataFrame: run, ball_position_m, the run's metrics."""
    def to_xarray(self) -> Any:
        """Every run as an xarray.Dataset on run (ball_position_m a coordinate, m)."""
    def as_dict(self, json: bool = False) -> Dict[str, Any]:
        """Every field in one dict; json=True: plain lists, numbers and None (NaN → None)."""
    def _repr_html_(self) -> str: ...

class Response:
    """The frequency response under the harmonic force: the fields of ``thud response --json``,
    each sweep's points as arrays."""

    design: Dict[str, object]
    """The design at the first frequency."""
    force_n: float
    """Force amplitude F0 (N)."""
    periods: int
    """Forcing periods of each steady-state window."""
    continuation: bool
    runs: int
    """Runs per frequency N (1: the single trajectory)."""
    sweeps: List[Dict[str, Any]]
    """One sweep from rest, or "up" then "down" with continuation. Each: "direction" and per
    frequency arrays freq_hz (Hz), amplitude_m, amplitude_linear_m (m; NaN: unbounded),
    reduction_db, leq_db (dB; NaN: no impact), impacts_per_period, periodic, settled,
    truncated (bool), window_start_s, window_end_s, final_time_s (s). With ensemble=N:
    freq_hz, amplitude_linear_m, periodic_fraction, settled_fraction, truncated, "spread"
    {metric: {"p10", "median", "p90"}} and "ensemble" (every run, 2-D: frequency × run)."""
    def to_dataframe(self) -> Any:
        """One row per frequency of each sweep as a pandas.DataFrame: direction, freq_hz, …"""
    def to_xarray(self) -> Any:
        """Every figure as an xarray.Dataset on direction × freq_hz (Hz)."""
    def as_dict(self, json: bool = False) -> Dict[str, Any]:
        """Every field in one dict; json=True: plain lists, numbers and None (NaN → None)."""
    def _repr_html_(self) -> str: ...
    def to_svg(self, path: Union[str, "os.PathLike[str]"], *, overwrite: bool = False, size: Optional[Tuple[float, float]] = None, title: bool = True) -> None:
        """The frequency response as SVG (``thud export svg response`` over these frequencies)."""
    def to_pdf(self, path: Union[str, "os.PathLike[str]"], *, overwrite: bool = False, size: Optional[Tuple[float, float]] = None, title: bool = True) -> None:
        """The frequency response as a one-page PDF (``thud export pdf response``)."""

def pulse(
    *,
    preset: Optional[str] = None,
    design: Union[str, "os.PathLike[str]", None] = None,  # A design file (what --save, fit --save and the explorer write) or a saved design's name, instead of preset
    mass: Optional[Quantity] = None,  # Sphere mass (kg, or e.g. 40.5g). Default: from --radius and --sphere's density, else 40.5 g; 0.0001 to 100 kg
    u0: Optional[Quantity] = None,  # Impact speed U0 (m/s) [default: 1.4]; 0.0001 to 100 m/s
    main_mass: Optional[Quantity] = None,  # Mass of a movable target (kg): K* = (m+M)/(mM) (Eq 8). Default: a fixed plate; 0.001 to 1e6 kg
    k_hz: Optional[Quantity] = None,  # Hertz stiffness K_HZ (N/m^1.5) [default: 5.6e8, or from --sphere/--plate]; 10000 to 1e13 N/m^1.5
    sphere: Optional[str] = None,  # Sphere material (steel, stainless-steel, acrylic, brass, aluminium, glass, rubber, nylon, tungsten-carbide)
    plate: Optional[str] = None,  # Plate material [default: steel when --sphere is given]
    density: Optional[Quantity] = None,  # Sphere density (kg/m³) [default: --sphere's]: with --mass the radius follows, with --radius the mass; 10 to 25000 kg/m^3
    radius: Optional[Quantity] = None,  # Sphere radius (m, or e.g. 19.05mm). Default: from --mass and --sphere's density, else 19.05 mm; 0.0001 to 2 m
    r: Optional[Quantity] = None,  # Observer distance from the contact point (m) [default: 0.7]; 0.001 to 1000 m
    theta: Optional[Quantity] = None,  # Observer angle from the plate's normal (degrees) [default: 45]; -180 to 180 deg
    source: Optional[Source] = None,  # Reflecting surfaces: a free sphere, a plate, or a wall–floor corner [default: dipole]
    quad_signs: Optional[QuadSigns] = None,  # Quadrupole wall-image signs: the paper's (pressure-release wall) or a rigid wall [default: rigid]
    pulse: Optional[PulseShape] = None,  # Acceleration pulse: the paper's half-sine (Eq 7) or the exact Hertz pulse [default: half-sine]
    model: Optional[Model] = None,  # The model of the world [default: paper]: physical is the measured level (peak, exact Hertz pulse, air from --air-temperature and --air-pressure, K_HZ and mass from the materials)
    air_temperature: Optional[Quantity] = None,  # Air temperature (°C) of the physical model: ρ0 and c follow [default: 20]; -60 to 60 degC
    air_pressure: Optional[Quantity] = None,  # Air pressure (Pa, or e.g. 101.325kPa) of the physical model: ρ0 follows [default: 101325]; 20000 to 2e5 Pa
    rho_c: Optional[Quantity] = None,  # Air impedance ρ0·c of the paper model (Pa·s/m) [default: 400, the paper's]; 1 to 1e7 Pa·s/m
    sound_speed: Optional[Quantity] = None,  # Speed of sound c of the paper model (m/s) [default: 343]; 1 to 10000 m/s
    points: Count = 2000,
    no_limit: bool = False,
) -> Pulse:
    """The pressure pulse of one Hertzian impact at an observer (Eqs 1–24), as ``thud pulse``.

    Defaults: the paper's Fig 2 impact — acrylic sphere a 19.05 mm, m 40.5 g, U0 1.4 m/s,
    K_HZ 5.6e8 N/m^1.5 on a fixed plate, dipole at r 0.7 m, θ 45°; or those of ``preset``.

    radius (m), mass (kg), density (kg/m³): the ball (two of the three, or one with the sphere's
    density), u0 (m/s), k_hz (N/m^1.5); sphere/plate: materials (K_HZ from Eq 2);
    main_mass (kg): a movable target (Eq 8); r (m), theta (degrees); rho_c (Pa·s/m),
    sound_speed (m/s); model: "paper" (default) or "physical" (peak level, exact Hertz pulse,
    air from air_temperature (°C) and air_pressure (Pa), K_HZ and mass from the materials);
    points: waveform points; no_limit: lift the work cap.
    """

@overload
def simulate(
    *,
    preset: Optional[str] = None,
    design: Union[str, "os.PathLike[str]", None] = None,  # A design file (what --save, fit --save and the explorer write) or a saved design's name, instead of preset
    mass: Optional[Quantity] = None,  # Impact mass m (kg, or e.g. 40.5g); 0.0001 to 100 kg
    gap: Optional[Quantity] = None,  # Total clearance d (m, or e.g. 4cm); 1e-5 to 10 m
    v0: Optional[Quantity] = None,  # Initial velocity of the main mass (m/s); -100 to 100 m/s
    main_mass: Optional[Quantity] = None,  # Main mass M (kg); 0.001 to 1e6 kg
    k: Optional[Quantity] = None,  # Spring stiffness K (N/m); 0 to 1e10 N/m
    c: Optional[Quantity] = None,  # Viscous damping C (N·s/m); 0 to 1e6 N·s/m
    c1: Optional[Quantity] = None,  # Contact damping c1 (N·s/m); 0 to 1e6 N·s/m
    k_hz: Optional[Quantity] = None,  # Hertz stiffness K_HZ (N/m^1.5); 10000 to 1e13 N/m^1.5
    sphere: Optional[str] = None,  # Ball material: K_HZ then follows from the materials and the ball's radius (Eq 2)
    plate: Optional[str] = None,  # Enclosure material (with --sphere) [default: steel]
    sphere_poisson: Optional[Quantity] = None,  # The ball's Poisson ratio ν in K_HZ (Eq 2), instead of its material's (with --sphere); 0 to 0.5
    no_tension: Optional[bool] = None,  # Clamp the contact force at ≥ 0 (a contact cannot pull)
    duration: Optional[Quantity] = None,  # Simulated time (s); 1e-6 to 1e6 s
    solver: Optional[Solver] = None,  # Solver
    dt: Optional[Quantity] = None,  # Newmark time step (s) [default: 1e-7]; 1e-14 to 0.001 s
    density: Optional[Quantity] = None,  # Ball density (kg/m³) [default: the --sphere material's]: with --mass the radius follows, with --radius the mass; 10 to 25000 kg/m^3
    radius: Optional[Quantity] = None,  # Ball radius (m): with --mass as given, else the mass follows from the density; 0.0001 to 2 m
    r: Optional[Quantity] = None,  # Observer distance (m); 0.001 to 1000 m
    theta: Optional[Quantity] = None,  # Observer angle (degrees); -180 to 180 deg
    source: Optional[Source] = None,  # Reflecting surfaces around the impact
    quad_signs: Optional[QuadSigns] = None,  # Quadrupole wall-image signs
    pulse: Optional[PulseShape] = None,  # Acceleration pulse of each impact's sound: half-sine (Eq 7) or the exact Hertz pulse
    model: Optional[Model] = None,  # The model of the world [default: paper]: physical is the level a microphone reads (peak, real air, materials)
    air_temperature: Optional[Quantity] = None,  # Air temperature (°C) of the physical model: ρ0 and c follow [default: 20]; -60 to 60 degC
    air_pressure: Optional[Quantity] = None,  # Air pressure (Pa, or e.g. 101.325kPa) of the physical model: ρ0 follows [default: 101325]; 20000 to 2e5 Pa
    rho_c: Optional[Quantity] = None,  # Air impedance ρ0·c of the paper model (Pa·s/m) [default: 400, the paper's]; 1 to 1e7 Pa·s/m
    sound_speed: Optional[Quantity] = None,  # Speed of sound c of the paper model (m/s) [default: 343]; 1 to 10000 m/s
    l_star: Optional[Quantity] = None,  # Zone threshold L* on SPLmax (dB); 0 to 200 dB
    e_star: Optional[Quantity] = None,  # Zone threshold e* on the damping inclination (cm/s); 0 to 1000 cm/s
    force: Optional[Quantity] = None,  # Amplitude F0 of a harmonic force F0·cos(2π·f·t) on the main mass (N, or e.g. 2N) [default: 0, the paper's free decay]; needs --freq; 0 to 1e6 N (alias force_amplitude)
    freq: Optional[Quantity] = None,  # Frequency f of the harmonic force (Hz, or e.g. 5Hz); 0.001 to 1e5 Hz
    ball_position: Optional[Quantity] = None,  # The ball's initial offset y0 from the enclosure's centre (m, or e.g. -1cm; |y0| < d/2) [default: 0, centred]; -5 to 5 m
    ball_velocity: Optional[Quantity] = None,  # The ball's initial velocity w0 (m/s) [default: 0]; -100 to 100 m/s
    periods: Optional[Count] = None,  # Forcing periods N of the steady-state window of a forced run [default: 10]; 1 to 1000 periods
    settle: Optional[bool] = None,  # Run a forced run on past --duration, N periods at a time, until its steady amplitude settles
    samples: Count = 2001,
    ensemble: Literal[1] = 1,
    no_limit: bool = False,
) -> Run:
    """One impact-damper design through its impacts (Eqs 25–27), as ``thud simulate``.

    preset: the starting design (default "default"; ``thud.presets()``), then: mass (kg),
    gap (m), v0 (m/s), main_mass (kg), k (N/m), c (N·s/m), c1 (N·s/m), k_hz (N/m^1.5),
    sphere/plate (materials), no_tension, duration (s), solver, dt (s, Newmark), density
    (kg/m³) or radius (m) of the ball, r (m), theta (degrees), source, quad_signs, pulse,
    l_star (dB), e_star (cm/s); force (N) and freq (Hz): the harmonic force F0·cos(2π·f·t) on
    the main mass; ball_position (m, |y0| < gap/2) and ball_velocity (m/s): the ball's start;
    periods: forcing periods of the steady-state window; settle: run on until it settles;
    samples: time-history samples; ensemble: N runs from ball offsets spread over the
    clearance (N > 1 returns an Ensemble; not with ball_position); no_limit: lift the work
    caps. Ctrl-C stops the run (KeyboardInterrupt).
    """

@overload
def simulate(
    *,
    preset: Optional[str] = None,
    design: Union[str, "os.PathLike[str]", None] = None,  # A design file (what --save, fit --save and the explorer write) or a saved design's name, instead of preset
    mass: Optional[Quantity] = None,  # Impact mass m (kg, or e.g. 40.5g); 0.0001 to 100 kg
    gap: Optional[Quantity] = None,  # Total clearance d (m, or e.g. 4cm); 1e-5 to 10 m
    v0: Optional[Quantity] = None,  # Initial velocity of the main mass (m/s); -100 to 100 m/s
    main_mass: Optional[Quantity] = None,  # Main mass M (kg); 0.001 to 1e6 kg
    k: Optional[Quantity] = None,  # Spring stiffness K (N/m); 0 to 1e10 N/m
    c: Optional[Quantity] = None,  # Viscous damping C (N·s/m); 0 to 1e6 N·s/m
    c1: Optional[Quantity] = None,  # Contact damping c1 (N·s/m); 0 to 1e6 N·s/m
    k_hz: Optional[Quantity] = None,  # Hertz stiffness K_HZ (N/m^1.5); 10000 to 1e13 N/m^1.5
    sphere: Optional[str] = None,  # Ball material: K_HZ then follows from the materials and the ball's radius (Eq 2)
    plate: Optional[str] = None,  # Enclosure material (with --sphere) [default: steel]
    sphere_poisson: Optional[Quantity] = None,  # The ball's Poisson ratio ν in K_HZ (Eq 2), instead of its material's (with --sphere); 0 to 0.5
    no_tension: Optional[bool] = None,  # Clamp the contact force at ≥ 0 (a contact cannot pull)
    duration: Optional[Quantity] = None,  # Simulated time (s); 1e-6 to 1e6 s
    solver: Optional[Solver] = None,  # Solver
    dt: Optional[Quantity] = None,  # Newmark time step (s) [default: 1e-7]; 1e-14 to 0.001 s
    density: Optional[Quantity] = None,  # Ball density (kg/m³) [default: the --sphere material's]: with --mass the radius follows, with --radius the mass; 10 to 25000 kg/m^3
    radius: Optional[Quantity] = None,  # Ball radius (m): with --mass as given, else the mass follows from the density; 0.0001 to 2 m
    r: Optional[Quantity] = None,  # Observer distance (m); 0.001 to 1000 m
    theta: Optional[Quantity] = None,  # Observer angle (degrees); -180 to 180 deg
    source: Optional[Source] = None,  # Reflecting surfaces around the impact
    quad_signs: Optional[QuadSigns] = None,  # Quadrupole wall-image signs
    pulse: Optional[PulseShape] = None,  # Acceleration pulse of each impact's sound: half-sine (Eq 7) or the exact Hertz pulse
    model: Optional[Model] = None,  # The model of the world [default: paper]: physical is the level a microphone reads (peak, real air, materials)
    air_temperature: Optional[Quantity] = None,  # Air temperature (°C) of the physical model: ρ0 and c follow [default: 20]; -60 to 60 degC
    air_pressure: Optional[Quantity] = None,  # Air pressure (Pa, or e.g. 101.325kPa) of the physical model: ρ0 follows [default: 101325]; 20000 to 2e5 Pa
    rho_c: Optional[Quantity] = None,  # Air impedance ρ0·c of the paper model (Pa·s/m) [default: 400, the paper's]; 1 to 1e7 Pa·s/m
    sound_speed: Optional[Quantity] = None,  # Speed of sound c of the paper model (m/s) [default: 343]; 1 to 10000 m/s
    l_star: Optional[Quantity] = None,  # Zone threshold L* on SPLmax (dB); 0 to 200 dB
    e_star: Optional[Quantity] = None,  # Zone threshold e* on the damping inclination (cm/s); 0 to 1000 cm/s
    force: Optional[Quantity] = None,  # Amplitude F0 of a harmonic force F0·cos(2π·f·t) on the main mass (N, or e.g. 2N) [default: 0, the paper's free decay]; needs --freq; 0 to 1e6 N (alias force_amplitude)
    freq: Optional[Quantity] = None,  # Frequency f of the harmonic force (Hz, or e.g. 5Hz); 0.001 to 1e5 Hz
    ball_position: Optional[Quantity] = None,  # The ball's initial offset y0 from the enclosure's centre (m, or e.g. -1cm; |y0| < d/2) [default: 0, centred]; -5 to 5 m
    ball_velocity: Optional[Quantity] = None,  # The ball's initial velocity w0 (m/s) [default: 0]; -100 to 100 m/s
    periods: Optional[Count] = None,  # Forcing periods N of the steady-state window of a forced run [default: 10]; 1 to 1000 periods
    settle: Optional[bool] = None,  # Run a forced run on past --duration, N periods at a time, until its steady amplitude settles
    samples: Count = 2001,
    ensemble: EnsembleSize,
    no_limit: bool = False,
) -> Ensemble: ...
@overload
def simulate(
    *,
    preset: Optional[str] = None,
    design: Union[str, "os.PathLike[str]", None] = None,  # A design file (what --save, fit --save and the explorer write) or a saved design's name, instead of preset
    mass: Optional[Quantity] = None,  # Impact mass m (kg, or e.g. 40.5g); 0.0001 to 100 kg
    gap: Optional[Quantity] = None,  # Total clearance d (m, or e.g. 4cm); 1e-5 to 10 m
    v0: Optional[Quantity] = None,  # Initial velocity of the main mass (m/s); -100 to 100 m/s
    main_mass: Optional[Quantity] = None,  # Main mass M (kg); 0.001 to 1e6 kg
    k: Optional[Quantity] = None,  # Spring stiffness K (N/m); 0 to 1e10 N/m
    c: Optional[Quantity] = None,  # Viscous damping C (N·s/m); 0 to 1e6 N·s/m
    c1: Optional[Quantity] = None,  # Contact damping c1 (N·s/m); 0 to 1e6 N·s/m
    k_hz: Optional[Quantity] = None,  # Hertz stiffness K_HZ (N/m^1.5); 10000 to 1e13 N/m^1.5
    sphere: Optional[str] = None,  # Ball material: K_HZ then follows from the materials and the ball's radius (Eq 2)
    plate: Optional[str] = None,  # Enclosure material (with --sphere) [default: steel]
    sphere_poisson: Optional[Quantity] = None,  # The ball's Poisson ratio ν in K_HZ (Eq 2), instead of its material's (with --sphere); 0 to 0.5
    no_tension: Optional[bool] = None,  # Clamp the contact force at ≥ 0 (a contact cannot pull)
    duration: Optional[Quantity] = None,  # Simulated time (s); 1e-6 to 1e6 s
    solver: Optional[Solver] = None,  # Solver
    dt: Optional[Quantity] = None,  # Newmark time step (s) [default: 1e-7]; 1e-14 to 0.001 s
    density: Optional[Quantity] = None,  # Ball density (kg/m³) [default: the --sphere material's]: with --mass the radius follows, with --radius the mass; 10 to 25000 kg/m^3
    radius: Optional[Quantity] = None,  # Ball radius (m): with --mass as given, else the mass follows from the density; 0.0001 to 2 m
    r: Optional[Quantity] = None,  # Observer distance (m); 0.001 to 1000 m
    theta: Optional[Quantity] = None,  # Observer angle (degrees); -180 to 180 deg
    source: Optional[Source] = None,  # Reflecting surfaces around the impact
    quad_signs: Optional[QuadSigns] = None,  # Quadrupole wall-image signs
    pulse: Optional[PulseShape] = None,  # Acceleration pulse of each impact's sound: half-sine (Eq 7) or the exact Hertz pulse
    model: Optional[Model] = None,  # The model of the world [default: paper]: physical is the level a microphone reads (peak, real air, materials)
    air_temperature: Optional[Quantity] = None,  # Air temperature (°C) of the physical model: ρ0 and c follow [default: 20]; -60 to 60 degC
    air_pressure: Optional[Quantity] = None,  # Air pressure (Pa, or e.g. 101.325kPa) of the physical model: ρ0 follows [default: 101325]; 20000 to 2e5 Pa
    rho_c: Optional[Quantity] = None,  # Air impedance ρ0·c of the paper model (Pa·s/m) [default: 400, the paper's]; 1 to 1e7 Pa·s/m
    sound_speed: Optional[Quantity] = None,  # Speed of sound c of the paper model (m/s) [default: 343]; 1 to 10000 m/s
    l_star: Optional[Quantity] = None,  # Zone threshold L* on SPLmax (dB); 0 to 200 dB
    e_star: Optional[Quantity] = None,  # Zone threshold e* on the damping inclination (cm/s); 0 to 1000 cm/s
    force: Optional[Quantity] = None,  # Amplitude F0 of a harmonic force F0·cos(2π·f·t) on the main mass (N, or e.g. 2N) [default: 0, the paper's free decay]; needs --freq; 0 to 1e6 N (alias force_amplitude)
    freq: Optional[Quantity] = None,  # Frequency f of the harmonic force (Hz, or e.g. 5Hz); 0.001 to 1e5 Hz
    ball_position: Optional[Quantity] = None,  # The ball's initial offset y0 from the enclosure's centre (m, or e.g. -1cm; |y0| < d/2) [default: 0, centred]; -5 to 5 m
    ball_velocity: Optional[Quantity] = None,  # The ball's initial velocity w0 (m/s) [default: 0]; -100 to 100 m/s
    periods: Optional[Count] = None,  # Forcing periods N of the steady-state window of a forced run [default: 10]; 1 to 1000 periods
    settle: Optional[bool] = None,  # Run a forced run on past --duration, N periods at a time, until its steady amplitude settles
    samples: Count = 2001,
    ensemble: Count = 1,
    no_limit: bool = False,
) -> Union[Run, Ensemble]: ...
def simulate_ensemble(
    runs: Count,
    *,
    preset: Optional[str] = None,
    design: Union[str, "os.PathLike[str]", None] = None,  # A design file (what --save, fit --save and the explorer write) or a saved design's name, instead of preset
    mass: Optional[Quantity] = None,  # Impact mass m (kg, or e.g. 40.5g); 0.0001 to 100 kg
    gap: Optional[Quantity] = None,  # Total clearance d (m, or e.g. 4cm); 1e-5 to 10 m
    v0: Optional[Quantity] = None,  # Initial velocity of the main mass (m/s); -100 to 100 m/s
    main_mass: Optional[Quantity] = None,  # Main mass M (kg); 0.001 to 1e6 kg
    k: Optional[Quantity] = None,  # Spring stiffness K (N/m); 0 to 1e10 N/m
    c: Optional[Quantity] = None,  # Viscous damping C (N·s/m); 0 to 1e6 N·s/m
    c1: Optional[Quantity] = None,  # Contact damping c1 (N·s/m); 0 to 1e6 N·s/m
    k_hz: Optional[Quantity] = None,  # Hertz stiffness K_HZ (N/m^1.5); 10000 to 1e13 N/m^1.5
    sphere: Optional[str] = None,  # Ball material: K_HZ then follows from the materials and the ball's radius (Eq 2)
    plate: Optional[str] = None,  # Enclosure material (with --sphere) [default: steel]
    sphere_poisson: Optional[Quantity] = None,  # The ball's Poisson ratio ν in K_HZ (Eq 2), instead of its material's (with --sphere); 0 to 0.5
    no_tension: Optional[bool] = None,  # Clamp the contact force at ≥ 0 (a contact cannot pull)
    duration: Optional[Quantity] = None,  # Simulated time (s); 1e-6 to 1e6 s
    solver: Optional[Solver] = None,  # Solver
    dt: Optional[Quantity] = None,  # Newmark time step (s) [default: 1e-7]; 1e-14 to 0.001 s
    density: Optional[Quantity] = None,  # Ball density (kg/m³) [default: the --sphere material's]: with --mass the radius follows, with --radius the mass; 10 to 25000 kg/m^3
    radius: Optional[Quantity] = None,  # Ball radius (m): with --mass as given, else the mass follows from the density; 0.0001 to 2 m
    r: Optional[Quantity] = None,  # Observer distance (m); 0.001 to 1000 m
    theta: Optional[Quantity] = None,  # Observer angle (degrees); -180 to 180 deg
    source: Optional[Source] = None,  # Reflecting surfaces around the impact
    quad_signs: Optional[QuadSigns] = None,  # Quadrupole wall-image signs
    pulse: Optional[PulseShape] = None,  # Acceleration pulse of each impact's sound: half-sine (Eq 7) or the exact Hertz pulse
    model: Optional[Model] = None,  # The model of the world [default: paper]: physical is the level a microphone reads (peak, real air, materials)
    air_temperature: Optional[Quantity] = None,  # Air temperature (°C) of the physical model: ρ0 and c follow [default: 20]; -60 to 60 degC
    air_pressure: Optional[Quantity] = None,  # Air pressure (Pa, or e.g. 101.325kPa) of the physical model: ρ0 follows [default: 101325]; 20000 to 2e5 Pa
    rho_c: Optional[Quantity] = None,  # Air impedance ρ0·c of the paper model (Pa·s/m) [default: 400, the paper's]; 1 to 1e7 Pa·s/m
    sound_speed: Optional[Quantity] = None,  # Speed of sound c of the paper model (m/s) [default: 343]; 1 to 10000 m/s
    l_star: Optional[Quantity] = None,  # Zone threshold L* on SPLmax (dB); 0 to 200 dB
    e_star: Optional[Quantity] = None,  # Zone threshold e* on the damping inclination (cm/s); 0 to 1000 cm/s
    force: Optional[Quantity] = None,  # Amplitude F0 of a harmonic force F0·cos(2π·f·t) on the main mass (N, or e.g. 2N) [default: 0, the paper's free decay]; needs --freq; 0 to 1e6 N (alias force_amplitude)
    freq: Optional[Quantity] = None,  # Frequency f of the harmonic force (Hz, or e.g. 5Hz); 0.001 to 1e5 Hz
    ball_velocity: Optional[Quantity] = None,  # The ball's initial velocity w0 (m/s) [default: 0]; -100 to 100 m/s
    periods: Optional[Count] = None,  # Forcing periods N of the steady-state window of a forced run [default: 10]; 1 to 1000 periods
    settle: Optional[bool] = None,  # Run a forced run on past --duration, N periods at a time, until its steady amplitude settles
    no_limit: bool = False,
) -> Ensemble:
    """One design from ``runs`` ball offsets y0 = −d/2 + (k + ½)·d/N at rest: always an
    Ensemble (even of one run), as ``simulate(ensemble=N)``; keywords as for ``simulate``."""

@overload
def sweep(
    masses_kg: Union[Sequence[Quantity], npt.ArrayLike, str],
    gaps_m: Union[Sequence[Quantity], npt.ArrayLike, str],
    *,
    preset: Optional[str] = None,
    design: Union[str, "os.PathLike[str]", None] = None,  # A design file (what --save, fit --save and the explorer write) or a saved design's name, instead of preset
    mass: Optional[Quantity] = None,  # Impact mass m (kg, or e.g. 40.5g); 0.0001 to 100 kg
    gap: Optional[Quantity] = None,  # Total clearance d (m, or e.g. 4cm); 1e-5 to 10 m
    v0: Optional[Quantity] = None,  # Initial velocity of the main mass (m/s); -100 to 100 m/s
    main_mass: Optional[Quantity] = None,  # Main mass M (kg); 0.001 to 1e6 kg
    k: Optional[Quantity] = None,  # Spring stiffness K (N/m); 0 to 1e10 N/m
    c: Optional[Quantity] = None,  # Viscous damping C (N·s/m); 0 to 1e6 N·s/m
    c1: Optional[Quantity] = None,  # Contact damping c1 (N·s/m); 0 to 1e6 N·s/m
    k_hz: Optional[Quantity] = None,  # Hertz stiffness K_HZ (N/m^1.5); 10000 to 1e13 N/m^1.5
    sphere: Optional[str] = None,  # Ball material: K_HZ then follows from the materials and the ball's radius (Eq 2)
    plate: Optional[str] = None,  # Enclosure material (with --sphere) [default: steel]
    sphere_poisson: Optional[Quantity] = None,  # The ball's Poisson ratio ν in K_HZ (Eq 2), instead of its material's (with --sphere); 0 to 0.5
    no_tension: Optional[bool] = None,  # Clamp the contact force at ≥ 0 (a contact cannot pull)
    duration: Optional[Quantity] = None,  # Simulated time (s); 1e-6 to 1e6 s
    solver: Optional[Solver] = None,  # Solver
    dt: Optional[Quantity] = None,  # Newmark time step (s) [default: 1e-7]; 1e-14 to 0.001 s
    density: Optional[Quantity] = None,  # Ball density (kg/m³) [default: the --sphere material's]: with --mass the radius follows, with --radius the mass; 10 to 25000 kg/m^3
    radius: Optional[Quantity] = None,  # Ball radius (m): with --mass as given, else the mass follows from the density; 0.0001 to 2 m
    r: Optional[Quantity] = None,  # Observer distance (m); 0.001 to 1000 m
    theta: Optional[Quantity] = None,  # Observer angle (degrees); -180 to 180 deg
    source: Optional[Source] = None,  # Reflecting surfaces around the impact
    quad_signs: Optional[QuadSigns] = None,  # Quadrupole wall-image signs
    pulse: Optional[PulseShape] = None,  # Acceleration pulse of each impact's sound: half-sine (Eq 7) or the exact Hertz pulse
    model: Optional[Model] = None,  # The model of the world [default: paper]: physical is the level a microphone reads (peak, real air, materials)
    air_temperature: Optional[Quantity] = None,  # Air temperature (°C) of the physical model: ρ0 and c follow [default: 20]; -60 to 60 degC
    air_pressure: Optional[Quantity] = None,  # Air pressure (Pa, or e.g. 101.325kPa) of the physical model: ρ0 follows [default: 101325]; 20000 to 2e5 Pa
    rho_c: Optional[Quantity] = None,  # Air impedance ρ0·c of the paper model (Pa·s/m) [default: 400, the paper's]; 1 to 1e7 Pa·s/m
    sound_speed: Optional[Quantity] = None,  # Speed of sound c of the paper model (m/s) [default: 343]; 1 to 10000 m/s
    l_star: Optional[Quantity] = None,  # Zone threshold L* on SPLmax (dB); 0 to 200 dB
    e_star: Optional[Quantity] = None,  # Zone threshold e* on the damping inclination (cm/s); 0 to 1000 cm/s
    force: Optional[Quantity] = None,  # Amplitude F0 of a harmonic force F0·cos(2π·f·t) on the main mass (N, or e.g. 2N) [default: 0, the paper's free decay]; needs --freq; 0 to 1e6 N (alias force_amplitude)
    freq: Optional[Quantity] = None,  # Frequency f of the harmonic force (Hz, or e.g. 5Hz); 0.001 to 1e5 Hz
    ball_position: Optional[Quantity] = None,  # The ball's initial offset y0 from the enclosure's centre (m, or e.g. -1cm; |y0| < d/2) [default: 0, centred]; -5 to 5 m
    ball_velocity: Optional[Quantity] = None,  # The ball's initial velocity w0 (m/s) [default: 0]; -100 to 100 m/s
    periods: Optional[Count] = None,  # Forcing periods N of the steady-state window of a forced run [default: 10]; 1 to 1000 periods
    settle: Optional[bool] = None,  # Run a forced run on past --duration, N periods at a time, until its steady amplitude settles
    ensemble: Count = 1,
    progress: ProgressArg = None,
    no_limit: bool = False,
) -> Chart:
    """The design chart (a Chart): the design run for every impact mass × gap on all cores, as
    ``thud sweep``. With design keywords given as sequences instead (``v0=np.linspace(1, 3,
    5), c1=[10, 20]``; mass × gap too), a study over any parameters as ``thud sweep --vary``:
    an xarray Dataset with one dimension per varied keyword (C order, units in attrs). masses_kg (kg) and gaps_m (m): sequences, or "FROM:TO:N" text as on the
    command line ("30g:100g:20" — N evenly spaced values, the command line's very numbers).
    Keywords as for ``simulate``; ensemble: N runs a cell (the metrics are then the medians,
    with zone3_probability, agreement, spread and every run). Ctrl-C stops the sweep.
    """
@overload
def sweep(
    masses_kg: None = None,
    gaps_m: None = None,
    *,
    preset: Optional[str] = None,
    design: Union[str, "os.PathLike[str]", None] = None,  # A design file (what --save, fit --save and the explorer write) or a saved design's name, instead of preset
    mass: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Impact mass m (kg, or e.g. 40.5g); 0.0001 to 100 kg
    gap: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Total clearance d (m, or e.g. 4cm); 1e-5 to 10 m
    v0: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Initial velocity of the main mass (m/s); -100 to 100 m/s
    main_mass: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Main mass M (kg); 0.001 to 1e6 kg
    k: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Spring stiffness K (N/m); 0 to 1e10 N/m
    c: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Viscous damping C (N·s/m); 0 to 1e6 N·s/m
    c1: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Contact damping c1 (N·s/m); 0 to 1e6 N·s/m
    k_hz: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Hertz stiffness K_HZ (N/m^1.5); 10000 to 1e13 N/m^1.5
    sphere: Optional[str] = None,  # Ball material: K_HZ then follows from the materials and the ball's radius (Eq 2)
    plate: Optional[str] = None,  # Enclosure material (with --sphere) [default: steel]
    sphere_poisson: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # The ball's Poisson ratio ν in K_HZ (Eq 2), instead of its material's (with --sphere); 0 to 0.5
    no_tension: Optional[bool] = None,  # Clamp the contact force at ≥ 0 (a contact cannot pull)
    duration: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Simulated time (s); 1e-6 to 1e6 s
    solver: Optional[Solver] = None,  # Solver
    dt: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Newmark time step (s) [default: 1e-7]; 1e-14 to 0.001 s
    density: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Ball density (kg/m³) [default: the --sphere material's]: with --mass the radius follows, with --radius the mass; 10 to 25000 kg/m^3
    radius: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Ball radius (m): with --mass as given, else the mass follows from the density; 0.0001 to 2 m
    r: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Observer distance (m); 0.001 to 1000 m
    theta: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Observer angle (degrees); -180 to 180 deg
    source: Optional[Source] = None,  # Reflecting surfaces around the impact
    quad_signs: Optional[QuadSigns] = None,  # Quadrupole wall-image signs
    pulse: Optional[PulseShape] = None,  # Acceleration pulse of each impact's sound: half-sine (Eq 7) or the exact Hertz pulse
    model: Optional[Model] = None,  # The model of the world [default: paper]: physical is the level a microphone reads (peak, real air, materials)
    air_temperature: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Air temperature (°C) of the physical model: ρ0 and c follow [default: 20]; -60 to 60 degC
    air_pressure: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Air pressure (Pa, or e.g. 101.325kPa) of the physical model: ρ0 follows [default: 101325]; 20000 to 2e5 Pa
    rho_c: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Air impedance ρ0·c of the paper model (Pa·s/m) [default: 400, the paper's]; 1 to 1e7 Pa·s/m
    sound_speed: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Speed of sound c of the paper model (m/s) [default: 343]; 1 to 10000 m/s
    l_star: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Zone threshold L* on SPLmax (dB); 0 to 200 dB
    e_star: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Zone threshold e* on the damping inclination (cm/s); 0 to 1000 cm/s
    force: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Amplitude F0 of a harmonic force F0·cos(2π·f·t) on the main mass (N, or e.g. 2N) [default: 0, the paper's free decay]; needs --freq; 0 to 1e6 N (alias force_amplitude)
    freq: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Frequency f of the harmonic force (Hz, or e.g. 5Hz); 0.001 to 1e5 Hz
    ball_position: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # The ball's initial offset y0 from the enclosure's centre (m, or e.g. -1cm; |y0| < d/2) [default: 0, centred]; -5 to 5 m
    ball_velocity: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # The ball's initial velocity w0 (m/s) [default: 0]; -100 to 100 m/s
    periods: Optional[Count] = None,  # Forcing periods N of the steady-state window of a forced run [default: 10]; 1 to 1000 periods
    settle: Optional[bool] = None,  # Run a forced run on past --duration, N periods at a time, until its steady amplitude settles
    ensemble: Count = 1,
    progress: ProgressArg = None,
    no_limit: bool = False,
) -> Any: ...

def bifurcation(
    *,
    preset: Optional[str] = None,
    design: Union[str, "os.PathLike[str]", None] = None,  # A design file (what --save, fit --save and the explorer write) or a saved design's name, instead of preset
    mass: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Impact mass m (kg, or e.g. 40.5g); 0.0001 to 100 kg
    gap: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Total clearance d (m, or e.g. 4cm); 1e-5 to 10 m
    v0: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Initial velocity of the main mass (m/s); -100 to 100 m/s
    main_mass: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Main mass M (kg); 0.001 to 1e6 kg
    k: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Spring stiffness K (N/m); 0 to 1e10 N/m
    c: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Viscous damping C (N·s/m); 0 to 1e6 N·s/m
    c1: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Contact damping c1 (N·s/m); 0 to 1e6 N·s/m
    k_hz: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Hertz stiffness K_HZ (N/m^1.5); 10000 to 1e13 N/m^1.5
    sphere: Optional[str] = None,  # Ball material: K_HZ then follows from the materials and the ball's radius (Eq 2)
    plate: Optional[str] = None,  # Enclosure material (with --sphere) [default: steel]
    sphere_poisson: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # The ball's Poisson ratio ν in K_HZ (Eq 2), instead of its material's (with --sphere); 0 to 0.5
    no_tension: Optional[bool] = None,  # Clamp the contact force at ≥ 0 (a contact cannot pull)
    duration: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Simulated time (s); 1e-6 to 1e6 s
    solver: Optional[Solver] = None,  # Solver
    dt: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Newmark time step (s) [default: 1e-7]; 1e-14 to 0.001 s
    density: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Ball density (kg/m³) [default: the --sphere material's]: with --mass the radius follows, with --radius the mass; 10 to 25000 kg/m^3
    radius: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Ball radius (m): with --mass as given, else the mass follows from the density; 0.0001 to 2 m
    r: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Observer distance (m); 0.001 to 1000 m
    theta: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Observer angle (degrees); -180 to 180 deg
    source: Optional[Source] = None,  # Reflecting surfaces around the impact
    quad_signs: Optional[QuadSigns] = None,  # Quadrupole wall-image signs
    pulse: Optional[PulseShape] = None,  # Acceleration pulse of each impact's sound: half-sine (Eq 7) or the exact Hertz pulse
    model: Optional[Model] = None,  # The model of the world [default: paper]: physical is the level a microphone reads (peak, real air, materials)
    air_temperature: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Air temperature (°C) of the physical model: ρ0 and c follow [default: 20]; -60 to 60 degC
    air_pressure: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Air pressure (Pa, or e.g. 101.325kPa) of the physical model: ρ0 follows [default: 101325]; 20000 to 2e5 Pa
    rho_c: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Air impedance ρ0·c of the paper model (Pa·s/m) [default: 400, the paper's]; 1 to 1e7 Pa·s/m
    sound_speed: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Speed of sound c of the paper model (m/s) [default: 343]; 1 to 10000 m/s
    l_star: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Zone threshold L* on SPLmax (dB); 0 to 200 dB
    e_star: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Zone threshold e* on the damping inclination (cm/s); 0 to 1000 cm/s
    force: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Amplitude F0 of a harmonic force F0·cos(2π·f·t) on the main mass (N, or e.g. 2N) [default: 0, the paper's free decay]; needs --freq; 0 to 1e6 N (alias force_amplitude)
    freq: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Frequency f of the harmonic force (Hz, or e.g. 5Hz); 0.001 to 1e5 Hz
    ball_position: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # The ball's initial offset y0 from the enclosure's centre (m, or e.g. -1cm; |y0| < d/2) [default: 0, centred]; -5 to 5 m
    ball_velocity: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # The ball's initial velocity w0 (m/s) [default: 0]; -100 to 100 m/s
    periods: Optional[Count] = None,  # Forcing periods N of the steady-state window of a forced run [default: 10]; 1 to 1000 periods
    settle: Optional[bool] = None,  # Run a forced run on past --duration, N periods at a time, until its steady amplitude settles
    transient: Count = 200,
    continuation: bool = False,
    branches: Optional[Count] = None,
    progress: ProgressArg = None,
    no_limit: bool = False,
) -> Any:
    """The bifurcation diagram of a forced design over the one keyword given as a sequence
    (``freq=np.linspace(3, 8, 200)``), as ``thud bifurcation --vary``: an xarray Dataset of the
    stroboscopic samples x(kT) on point × period, the impacts on point × impact, each point's
    value, direction and orbit type ("2/1", "4/2", "chaotic", "not settled"); periods: the
    sampled periods (default 100 here); transient: periods run first (default 200). The
    Dataset draws its diagram: ``ds.to_svg(path)``, ``ds.to_pdf(path)`` (``thud bifurcation
    --svg|--pdf``, byte for byte); branches=N draws the periodic orbits' branches continued
    from N seed values over its x(kT) panel (``--branches N``)."""

def response(
    freqs_hz: Union[Sequence[Quantity], npt.ArrayLike, str, None] = None,
    *,
    preset: Optional[str] = None,
    design: Union[str, "os.PathLike[str]", None] = None,  # A design file (what --save, fit --save and the explorer write) or a saved design's name, instead of preset
    mass: Optional[Quantity] = None,  # Impact mass m (kg, or e.g. 40.5g); 0.0001 to 100 kg
    gap: Optional[Quantity] = None,  # Total clearance d (m, or e.g. 4cm); 1e-5 to 10 m
    v0: Optional[Quantity] = None,  # Initial velocity of the main mass (m/s); -100 to 100 m/s
    main_mass: Optional[Quantity] = None,  # Main mass M (kg); 0.001 to 1e6 kg
    k: Optional[Quantity] = None,  # Spring stiffness K (N/m); 0 to 1e10 N/m
    c: Optional[Quantity] = None,  # Viscous damping C (N·s/m); 0 to 1e6 N·s/m
    c1: Optional[Quantity] = None,  # Contact damping c1 (N·s/m); 0 to 1e6 N·s/m
    k_hz: Optional[Quantity] = None,  # Hertz stiffness K_HZ (N/m^1.5); 10000 to 1e13 N/m^1.5
    sphere: Optional[str] = None,  # Ball material: K_HZ then follows from the materials and the ball's radius (Eq 2)
    plate: Optional[str] = None,  # Enclosure material (with --sphere) [default: steel]
    sphere_poisson: Optional[Quantity] = None,  # The ball's Poisson ratio ν in K_HZ (Eq 2), instead of its material's (with --sphere); 0 to 0.5
    no_tension: Optional[bool] = None,  # Clamp the contact force at ≥ 0 (a contact cannot pull)
    duration: Optional[Quantity] = None,  # Simulated time (s); 1e-6 to 1e6 s
    solver: Optional[Solver] = None,  # Solver
    dt: Optional[Quantity] = None,  # Newmark time step (s) [default: 1e-7]; 1e-14 to 0.001 s
    density: Optional[Quantity] = None,  # Ball density (kg/m³) [default: the --sphere material's]: with --mass the radius follows, with --radius the mass; 10 to 25000 kg/m^3
    radius: Optional[Quantity] = None,  # Ball radius (m): with --mass as given, else the mass follows from the density; 0.0001 to 2 m
    r: Optional[Quantity] = None,  # Observer distance (m); 0.001 to 1000 m
    theta: Optional[Quantity] = None,  # Observer angle (degrees); -180 to 180 deg
    source: Optional[Source] = None,  # Reflecting surfaces around the impact
    quad_signs: Optional[QuadSigns] = None,  # Quadrupole wall-image signs
    pulse: Optional[PulseShape] = None,  # Acceleration pulse of each impact's sound: half-sine (Eq 7) or the exact Hertz pulse
    model: Optional[Model] = None,  # The model of the world [default: paper]: physical is the level a microphone reads (peak, real air, materials)
    air_temperature: Optional[Quantity] = None,  # Air temperature (°C) of the physical model: ρ0 and c follow [default: 20]; -60 to 60 degC
    air_pressure: Optional[Quantity] = None,  # Air pressure (Pa, or e.g. 101.325kPa) of the physical model: ρ0 follows [default: 101325]; 20000 to 2e5 Pa
    rho_c: Optional[Quantity] = None,  # Air impedance ρ0·c of the paper model (Pa·s/m) [default: 400, the paper's]; 1 to 1e7 Pa·s/m
    sound_speed: Optional[Quantity] = None,  # Speed of sound c of the paper model (m/s) [default: 343]; 1 to 10000 m/s
    l_star: Optional[Quantity] = None,  # Zone threshold L* on SPLmax (dB); 0 to 200 dB
    e_star: Optional[Quantity] = None,  # Zone threshold e* on the damping inclination (cm/s); 0 to 1000 cm/s
    force: Optional[Quantity] = None,  # Amplitude F0 of a harmonic force F0·cos(2π·f·t) on the main mass (N, or e.g. 2N) [default: 0, the paper's free decay]; needs --freq; 0 to 1e6 N (alias force_amplitude)
    ball_position: Optional[Quantity] = None,  # The ball's initial offset y0 from the enclosure's centre (m, or e.g. -1cm; |y0| < d/2) [default: 0, centred]; -5 to 5 m
    ball_velocity: Optional[Quantity] = None,  # The ball's initial velocity w0 (m/s) [default: 0]; -100 to 100 m/s
    periods: Optional[Count] = None,  # Forcing periods N of the steady-state window of a forced run [default: 10]; 1 to 1000 periods
    settle: Optional[bool] = None,  # Run a forced run on past --duration, N periods at a time, until its steady amplitude settles
    continuation: bool = False,
    ensemble: Count = 1,
    progress: ProgressArg = None,
    no_limit: bool = False,
) -> Response:
    """The frequency response under the harmonic force F0·cos(2π·f·t) on the main mass, as
    ``thud response``: per frequency the steady amplitude with the damper beside the closed
    form without it (m), the cut (dB), impacts per period and Leq (dB re 20 µPa), settled.
    freqs_hz (Hz): a sequence, or "FROM:TO:N" text ("3Hz:8Hz:101"); None: 0.6–1.6 × the
    natural frequency, 101 points (the command line's default). force (N) is needed; each
    frequency starts from rest unless v0, ball_position or ball_velocity is given;
    continuation: each from the previous final state, up then down; ensemble: N runs a
    frequency (p10/median/p90 of each figure). Ctrl-C stops the response.
    """

class Orbit:
    """A periodic orbit of a forced design found by shooting (``thud.orbit``; ``thud orbit
    --json``). SI units."""

    design: Dict[str, Any]
    periods: int
    impacts_per_orbit: int
    symmetric: bool
    x_m: float
    v_m_s: float
    z_m: float
    zdot_m_s: float
    amplitude_m: float
    amplitude_linear_m: Optional[float]
    impacts: Dict[str, np.ndarray]
    multipliers: npt.NDArray[np.complex128]
    stable: bool
    critical: str
    residual: float
    iterations: int
    periods_simulated: float
    @property
    def label(self) -> str: ...
    def to_dataframe(self) -> Any: ...
    def to_xarray(self) -> Any: ...
    def as_dict(self, json: bool = False) -> Dict[str, Any]: ...

class ImpactMap:
    """A forced design's stroboscopic samples and impacts after a transient, and its orbit's
    type (``thud.impact_map``; ``thud impact-map --json``)."""

    design: Dict[str, Any]
    settings: Dict[str, int]
    orbit: str
    amplitude_m: float
    truncated: bool
    samples: Dict[str, np.ndarray]
    impacts: Dict[str, np.ndarray]
    def to_dataframe(self) -> Any: ...
    def to_xarray(self) -> Any: ...
    def as_dict(self, json: bool = False) -> Dict[str, Any]: ...
    def to_svg(self, path: Union[str, "os.PathLike[str]"], *, overwrite: bool = False, size: Optional[Tuple[float, float]] = None, title: bool = True) -> None: ...
    def to_pdf(self, path: Union[str, "os.PathLike[str]"], *, overwrite: bool = False, size: Optional[Tuple[float, float]] = None, title: bool = True) -> None: ...

def orbit(
    *,
    preset: Optional[str] = None,
    design: Union[str, "os.PathLike[str]", None] = None,  # A design file (what --save, fit --save and the explorer write) or a saved design's name, instead of preset
    mass: Optional[Quantity] = None,  # Impact mass m (kg, or e.g. 40.5g); 0.0001 to 100 kg
    gap: Optional[Quantity] = None,  # Total clearance d (m, or e.g. 4cm); 1e-5 to 10 m
    v0: Optional[Quantity] = None,  # Initial velocity of the main mass (m/s); -100 to 100 m/s
    main_mass: Optional[Quantity] = None,  # Main mass M (kg); 0.001 to 1e6 kg
    k: Optional[Quantity] = None,  # Spring stiffness K (N/m); 0 to 1e10 N/m
    c: Optional[Quantity] = None,  # Viscous damping C (N·s/m); 0 to 1e6 N·s/m
    c1: Optional[Quantity] = None,  # Contact damping c1 (N·s/m); 0 to 1e6 N·s/m
    k_hz: Optional[Quantity] = None,  # Hertz stiffness K_HZ (N/m^1.5); 10000 to 1e13 N/m^1.5
    sphere: Optional[str] = None,  # Ball material: K_HZ then follows from the materials and the ball's radius (Eq 2)
    plate: Optional[str] = None,  # Enclosure material (with --sphere) [default: steel]
    sphere_poisson: Optional[Quantity] = None,  # The ball's Poisson ratio ν in K_HZ (Eq 2), instead of its material's (with --sphere); 0 to 0.5
    no_tension: Optional[bool] = None,  # Clamp the contact force at ≥ 0 (a contact cannot pull)
    duration: Optional[Quantity] = None,  # Simulated time (s); 1e-6 to 1e6 s
    solver: Optional[Solver] = None,  # Solver
    dt: Optional[Quantity] = None,  # Newmark time step (s) [default: 1e-7]; 1e-14 to 0.001 s
    density: Optional[Quantity] = None,  # Ball density (kg/m³) [default: the --sphere material's]: with --mass the radius follows, with --radius the mass; 10 to 25000 kg/m^3
    radius: Optional[Quantity] = None,  # Ball radius (m): with --mass as given, else the mass follows from the density; 0.0001 to 2 m
    r: Optional[Quantity] = None,  # Observer distance (m); 0.001 to 1000 m
    theta: Optional[Quantity] = None,  # Observer angle (degrees); -180 to 180 deg
    source: Optional[Source] = None,  # Reflecting surfaces around the impact
    quad_signs: Optional[QuadSigns] = None,  # Quadrupole wall-image signs
    pulse: Optional[PulseShape] = None,  # Acceleration pulse of each impact's sound: half-sine (Eq 7) or the exact Hertz pulse
    model: Optional[Model] = None,  # The model of the world [default: paper]: physical is the level a microphone reads (peak, real air, materials)
    air_temperature: Optional[Quantity] = None,  # Air temperature (°C) of the physical model: ρ0 and c follow [default: 20]; -60 to 60 degC
    air_pressure: Optional[Quantity] = None,  # Air pressure (Pa, or e.g. 101.325kPa) of the physical model: ρ0 follows [default: 101325]; 20000 to 2e5 Pa
    rho_c: Optional[Quantity] = None,  # Air impedance ρ0·c of the paper model (Pa·s/m) [default: 400, the paper's]; 1 to 1e7 Pa·s/m
    sound_speed: Optional[Quantity] = None,  # Speed of sound c of the paper model (m/s) [default: 343]; 1 to 10000 m/s
    l_star: Optional[Quantity] = None,  # Zone threshold L* on SPLmax (dB); 0 to 200 dB
    e_star: Optional[Quantity] = None,  # Zone threshold e* on the damping inclination (cm/s); 0 to 1000 cm/s
    force: Optional[Quantity] = None,  # Amplitude F0 of a harmonic force F0·cos(2π·f·t) on the main mass (N, or e.g. 2N) [default: 0, the paper's free decay]; needs --freq; 0 to 1e6 N (alias force_amplitude)
    freq: Optional[Quantity] = None,  # Frequency f of the harmonic force (Hz, or e.g. 5Hz); 0.001 to 1e5 Hz
    ball_position: Optional[Quantity] = None,  # The ball's initial offset y0 from the enclosure's centre (m, or e.g. -1cm; |y0| < d/2) [default: 0, centred]; -5 to 5 m
    ball_velocity: Optional[Quantity] = None,  # The ball's initial velocity w0 (m/s) [default: 0]; -100 to 100 m/s
    periods: Optional[Count] = None,  # Forcing periods N of the steady-state window of a forced run [default: 10]; 1 to 1000 periods
    settle: Optional[bool] = None,  # Run a forced run on past --duration, N periods at a time, until its steady amplitude settles
    period: Optional[Count] = None,
    symmetric: bool = False,
    guess: Optional[Sequence[Quantity]] = None,
) -> Orbit:
    """The periodic orbit of a forced design found by shooting, stable or not, as ``thud
    orbit``: period (forcing periods, 1 to 16), symmetric, guess ((x, v, z, zdot) at phase 0)."""

def continuation(
    *,
    preset: Optional[str] = None,
    design: Union[str, "os.PathLike[str]", None] = None,  # A design file (what --save, fit --save and the explorer write) or a saved design's name, instead of preset
    mass: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Impact mass m (kg, or e.g. 40.5g); 0.0001 to 100 kg
    gap: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Total clearance d (m, or e.g. 4cm); 1e-5 to 10 m
    v0: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Initial velocity of the main mass (m/s); -100 to 100 m/s
    main_mass: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Main mass M (kg); 0.001 to 1e6 kg
    k: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Spring stiffness K (N/m); 0 to 1e10 N/m
    c: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Viscous damping C (N·s/m); 0 to 1e6 N·s/m
    c1: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Contact damping c1 (N·s/m); 0 to 1e6 N·s/m
    k_hz: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Hertz stiffness K_HZ (N/m^1.5); 10000 to 1e13 N/m^1.5
    sphere: Optional[str] = None,  # Ball material: K_HZ then follows from the materials and the ball's radius (Eq 2)
    plate: Optional[str] = None,  # Enclosure material (with --sphere) [default: steel]
    sphere_poisson: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # The ball's Poisson ratio ν in K_HZ (Eq 2), instead of its material's (with --sphere); 0 to 0.5
    no_tension: Optional[bool] = None,  # Clamp the contact force at ≥ 0 (a contact cannot pull)
    duration: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Simulated time (s); 1e-6 to 1e6 s
    solver: Optional[Solver] = None,  # Solver
    dt: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Newmark time step (s) [default: 1e-7]; 1e-14 to 0.001 s
    density: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Ball density (kg/m³) [default: the --sphere material's]: with --mass the radius follows, with --radius the mass; 10 to 25000 kg/m^3
    radius: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Ball radius (m): with --mass as given, else the mass follows from the density; 0.0001 to 2 m
    r: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Observer distance (m); 0.001 to 1000 m
    theta: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Observer angle (degrees); -180 to 180 deg
    source: Optional[Source] = None,  # Reflecting surfaces around the impact
    quad_signs: Optional[QuadSigns] = None,  # Quadrupole wall-image signs
    pulse: Optional[PulseShape] = None,  # Acceleration pulse of each impact's sound: half-sine (Eq 7) or the exact Hertz pulse
    model: Optional[Model] = None,  # The model of the world [default: paper]: physical is the level a microphone reads (peak, real air, materials)
    air_temperature: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Air temperature (°C) of the physical model: ρ0 and c follow [default: 20]; -60 to 60 degC
    air_pressure: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Air pressure (Pa, or e.g. 101.325kPa) of the physical model: ρ0 follows [default: 101325]; 20000 to 2e5 Pa
    rho_c: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Air impedance ρ0·c of the paper model (Pa·s/m) [default: 400, the paper's]; 1 to 1e7 Pa·s/m
    sound_speed: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Speed of sound c of the paper model (m/s) [default: 343]; 1 to 10000 m/s
    l_star: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Zone threshold L* on SPLmax (dB); 0 to 200 dB
    e_star: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Zone threshold e* on the damping inclination (cm/s); 0 to 1000 cm/s
    force: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Amplitude F0 of a harmonic force F0·cos(2π·f·t) on the main mass (N, or e.g. 2N) [default: 0, the paper's free decay]; needs --freq; 0 to 1e6 N (alias force_amplitude)
    freq: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # Frequency f of the harmonic force (Hz, or e.g. 5Hz); 0.001 to 1e5 Hz
    ball_position: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # The ball's initial offset y0 from the enclosure's centre (m, or e.g. -1cm; |y0| < d/2) [default: 0, centred]; -5 to 5 m
    ball_velocity: Union[Quantity, Sequence[Quantity], npt.ArrayLike, None] = None,  # The ball's initial velocity w0 (m/s) [default: 0]; -100 to 100 m/s
    periods: Optional[Count] = None,  # Forcing periods N of the steady-state window of a forced run [default: 10]; 1 to 1000 periods
    settle: Optional[bool] = None,  # Run a forced run on past --duration, N periods at a time, until its steady amplitude settles
    period: Optional[Count] = None,
    symmetric: bool = False,
) -> Any:
    """The family of periodic orbits continued over the one keyword given as (FROM, TO), as
    ``thud continue``: an xarray Dataset on point (value, orbit, stability, amplitude) and
    special (fold, period doubling, Neimark–Sacker, branch point, grazing). The Dataset draws
    its figure: ``ds.to_svg(path)``, ``ds.to_pdf(path)`` (``thud continue --svg|--pdf``, byte
    for byte)."""

def impact_map(
    *,
    preset: Optional[str] = None,
    design: Union[str, "os.PathLike[str]", None] = None,  # A design file (what --save, fit --save and the explorer write) or a saved design's name, instead of preset
    mass: Optional[Quantity] = None,  # Impact mass m (kg, or e.g. 40.5g); 0.0001 to 100 kg
    gap: Optional[Quantity] = None,  # Total clearance d (m, or e.g. 4cm); 1e-5 to 10 m
    v0: Optional[Quantity] = None,  # Initial velocity of the main mass (m/s); -100 to 100 m/s
    main_mass: Optional[Quantity] = None,  # Main mass M (kg); 0.001 to 1e6 kg
    k: Optional[Quantity] = None,  # Spring stiffness K (N/m); 0 to 1e10 N/m
    c: Optional[Quantity] = None,  # Viscous damping C (N·s/m); 0 to 1e6 N·s/m
    c1: Optional[Quantity] = None,  # Contact damping c1 (N·s/m); 0 to 1e6 N·s/m
    k_hz: Optional[Quantity] = None,  # Hertz stiffness K_HZ (N/m^1.5); 10000 to 1e13 N/m^1.5
    sphere: Optional[str] = None,  # Ball material: K_HZ then follows from the materials and the ball's radius (Eq 2)
    plate: Optional[str] = None,  # Enclosure material (with --sphere) [default: steel]
    sphere_poisson: Optional[Quantity] = None,  # The ball's Poisson ratio ν in K_HZ (Eq 2), instead of its material's (with --sphere); 0 to 0.5
    no_tension: Optional[bool] = None,  # Clamp the contact force at ≥ 0 (a contact cannot pull)
    duration: Optional[Quantity] = None,  # Simulated time (s); 1e-6 to 1e6 s
    solver: Optional[Solver] = None,  # Solver
    dt: Optional[Quantity] = None,  # Newmark time step (s) [default: 1e-7]; 1e-14 to 0.001 s
    density: Optional[Quantity] = None,  # Ball density (kg/m³) [default: the --sphere material's]: with --mass the radius follows, with --radius the mass; 10 to 25000 kg/m^3
    radius: Optional[Quantity] = None,  # Ball radius (m): with --mass as given, else the mass follows from the density; 0.0001 to 2 m
    r: Optional[Quantity] = None,  # Observer distance (m); 0.001 to 1000 m
    theta: Optional[Quantity] = None,  # Observer angle (degrees); -180 to 180 deg
    source: Optional[Source] = None,  # Reflecting surfaces around the impact
    quad_signs: Optional[QuadSigns] = None,  # Quadrupole wall-image signs
    pulse: Optional[PulseShape] = None,  # Acceleration pulse of each impact's sound: half-sine (Eq 7) or the exact Hertz pulse
    model: Optional[Model] = None,  # The model of the world [default: paper]: physical is the level a microphone reads (peak, real air, materials)
    air_temperature: Optional[Quantity] = None,  # Air temperature (°C) of the physical model: ρ0 and c follow [default: 20]; -60 to 60 degC
    air_pressure: Optional[Quantity] = None,  # Air pressure (Pa, or e.g. 101.325kPa) of the physical model: ρ0 follows [default: 101325]; 20000 to 2e5 Pa
    rho_c: Optional[Quantity] = None,  # Air impedance ρ0·c of the paper model (Pa·s/m) [default: 400, the paper's]; 1 to 1e7 Pa·s/m
    sound_speed: Optional[Quantity] = None,  # Speed of sound c of the paper model (m/s) [default: 343]; 1 to 10000 m/s
    l_star: Optional[Quantity] = None,  # Zone threshold L* on SPLmax (dB); 0 to 200 dB
    e_star: Optional[Quantity] = None,  # Zone threshold e* on the damping inclination (cm/s); 0 to 1000 cm/s
    force: Optional[Quantity] = None,  # Amplitude F0 of a harmonic force F0·cos(2π·f·t) on the main mass (N, or e.g. 2N) [default: 0, the paper's free decay]; needs --freq; 0 to 1e6 N (alias force_amplitude)
    freq: Optional[Quantity] = None,  # Frequency f of the harmonic force (Hz, or e.g. 5Hz); 0.001 to 1e5 Hz
    ball_position: Optional[Quantity] = None,  # The ball's initial offset y0 from the enclosure's centre (m, or e.g. -1cm; |y0| < d/2) [default: 0, centred]; -5 to 5 m
    ball_velocity: Optional[Quantity] = None,  # The ball's initial velocity w0 (m/s) [default: 0]; -100 to 100 m/s
    periods: Optional[Count] = None,  # Forcing periods N of the steady-state window of a forced run [default: 10]; 1 to 1000 periods
    settle: Optional[bool] = None,  # Run a forced run on past --duration, N periods at a time, until its steady amplitude settles
    transient: Count = 200,
    no_limit: bool = False,
) -> ImpactMap:
    """The impact map of a forced design, as ``thud impact-map``: stroboscopic samples and
    impacts over the sampled periods after ``transient`` ones, and the orbit's type."""

class Basins:
    """The basins of attraction of a forced design over the ball's start (``thud.basins``;
    ``thud basins --json``)."""

    design: Dict[str, Any]
    y0_m: FloatArray
    w0_m_s: FloatArray
    attractor: npt.NDArray[np.int64]
    amplitude_m: FloatArray
    attractors: List[Dict[str, Any]]
    def to_dataframe(self) -> Any: ...
    def to_xarray(self) -> Any: ...
    def as_dict(self, json: bool = False) -> Dict[str, Any]: ...
    def to_svg(self, path: Union[str, "os.PathLike[str]"], *, overwrite: bool = False, size: Optional[Tuple[float, float]] = None, title: bool = True) -> None: ...
    def to_pdf(self, path: Union[str, "os.PathLike[str]"], *, overwrite: bool = False, size: Optional[Tuple[float, float]] = None, title: bool = True) -> None: ...

class Restitution:
    """R = u_out/U0 of one isolated contact against the impact mass (``thud.restitution``)."""

    design: Dict[str, Any]
    u0_m_s: float
    target: Optional[float]
    masses_kg: FloatArray
    restitution: FloatArray
    c1_for_target_n_s_m: Optional[FloatArray]
    def to_dataframe(self) -> Any: ...
    def to_xarray(self) -> Any: ...
    def as_dict(self, json: bool = False) -> Dict[str, Any]: ...
    def to_svg(self, path: Union[str, "os.PathLike[str]"], *, overwrite: bool = False, size: Optional[Tuple[float, float]] = None, title: bool = True) -> None: ...
    def to_pdf(self, path: Union[str, "os.PathLike[str]"], *, overwrite: bool = False, size: Optional[Tuple[float, float]] = None, title: bool = True) -> None: ...

def basins(
    grid: Count = 20,
    w0: Tuple[Quantity, Quantity] = (-1.0, 1.0),
    *,
    preset: Optional[str] = None,
    design: Union[str, "os.PathLike[str]", None] = None,  # A design file (what --save, fit --save and the explorer write) or a saved design's name, instead of preset
    mass: Optional[Quantity] = None,  # Impact mass m (kg, or e.g. 40.5g); 0.0001 to 100 kg
    gap: Optional[Quantity] = None,  # Total clearance d (m, or e.g. 4cm); 1e-5 to 10 m
    v0: Optional[Quantity] = None,  # Initial velocity of the main mass (m/s); -100 to 100 m/s
    main_mass: Optional[Quantity] = None,  # Main mass M (kg); 0.001 to 1e6 kg
    k: Optional[Quantity] = None,  # Spring stiffness K (N/m); 0 to 1e10 N/m
    c: Optional[Quantity] = None,  # Viscous damping C (N·s/m); 0 to 1e6 N·s/m
    c1: Optional[Quantity] = None,  # Contact damping c1 (N·s/m); 0 to 1e6 N·s/m
    k_hz: Optional[Quantity] = None,  # Hertz stiffness K_HZ (N/m^1.5); 10000 to 1e13 N/m^1.5
    sphere: Optional[str] = None,  # Ball material: K_HZ then follows from the materials and the ball's radius (Eq 2)
    plate: Optional[str] = None,  # Enclosure material (with --sphere) [default: steel]
    sphere_poisson: Optional[Quantity] = None,  # The ball's Poisson ratio ν in K_HZ (Eq 2), instead of its material's (with --sphere); 0 to 0.5
    no_tension: Optional[bool] = None,  # Clamp the contact force at ≥ 0 (a contact cannot pull)
    duration: Optional[Quantity] = None,  # Simulated time (s); 1e-6 to 1e6 s
    solver: Optional[Solver] = None,  # Solver
    dt: Optional[Quantity] = None,  # Newmark time step (s) [default: 1e-7]; 1e-14 to 0.001 s
    density: Optional[Quantity] = None,  # Ball density (kg/m³) [default: the --sphere material's]: with --mass the radius follows, with --radius the mass; 10 to 25000 kg/m^3
    radius: Optional[Quantity] = None,  # Ball radius (m): with --mass as given, else the mass follows from the density; 0.0001 to 2 m
    r: Optional[Quantity] = None,  # Observer distance (m); 0.001 to 1000 m
    theta: Optional[Quantity] = None,  # Observer angle (degrees); -180 to 180 deg
    source: Optional[Source] = None,  # Reflecting surfaces around the impact
    quad_signs: Optional[QuadSigns] = None,  # Quadrupole wall-image signs
    pulse: Optional[PulseShape] = None,  # Acceleration pulse of each impact's sound: half-sine (Eq 7) or the exact Hertz pulse
    model: Optional[Model] = None,  # The model of the world [default: paper]: physical is the level a microphone reads (peak, real air, materials)
    air_temperature: Optional[Quantity] = None,  # Air temperature (°C) of the physical model: ρ0 and c follow [default: 20]; -60 to 60 degC
    air_pressure: Optional[Quantity] = None,  # Air pressure (Pa, or e.g. 101.325kPa) of the physical model: ρ0 follows [default: 101325]; 20000 to 2e5 Pa
    l_star: Optional[Quantity] = None,  # Zone threshold L* on SPLmax (dB); 0 to 200 dB
    e_star: Optional[Quantity] = None,  # Zone threshold e* on the damping inclination (cm/s); 0 to 1000 cm/s
    force: Optional[Quantity] = None,  # Amplitude F0 of a harmonic force F0·cos(2π·f·t) on the main mass (N, or e.g. 2N) [default: 0, the paper's free decay]; needs --freq; 0 to 1e6 N (alias force_amplitude)
    freq: Optional[Quantity] = None,  # Frequency f of the harmonic force (Hz, or e.g. 5Hz); 0.001 to 1e5 Hz
    periods: Optional[Count] = None,  # Forcing periods N of the steady-state window of a forced run [default: 10]; 1 to 1000 periods
    settle: Optional[bool] = None,  # Run a forced run on past --duration, N periods at a time, until its steady amplitude settles
    transient: Count = 200,
    no_limit: bool = False,
) -> Basins:
    """The basins of attraction over the ball's start, as ``thud basins``: grid × grid starts
    (y0 across the clearance, w0 over ``w0`` in m/s)."""

def restitution(
    masses_kg: Union[Sequence[Quantity], npt.ArrayLike, str] = "5g:100g:20",
    u0: Quantity = 1.4,
    target: Optional[Quantity] = None,
    *,
    preset: Optional[str] = None,
    design: Union[str, "os.PathLike[str]", None] = None,  # A design file (what --save, fit --save and the explorer write) or a saved design's name, instead of preset
    mass: Optional[Quantity] = None,  # Impact mass m (kg, or e.g. 40.5g); 0.0001 to 100 kg
    gap: Optional[Quantity] = None,  # Total clearance d (m, or e.g. 4cm); 1e-5 to 10 m
    v0: Optional[Quantity] = None,  # Initial velocity of the main mass (m/s); -100 to 100 m/s
    main_mass: Optional[Quantity] = None,  # Main mass M (kg); 0.001 to 1e6 kg
    k: Optional[Quantity] = None,  # Spring stiffness K (N/m); 0 to 1e10 N/m
    c: Optional[Quantity] = None,  # Viscous damping C (N·s/m); 0 to 1e6 N·s/m
    c1: Optional[Quantity] = None,  # Contact damping c1 (N·s/m); 0 to 1e6 N·s/m
    k_hz: Optional[Quantity] = None,  # Hertz stiffness K_HZ (N/m^1.5); 10000 to 1e13 N/m^1.5
    sphere: Optional[str] = None,  # Ball material: K_HZ then follows from the materials and the ball's radius (Eq 2)
    plate: Optional[str] = None,  # Enclosure material (with --sphere) [default: steel]
    sphere_poisson: Optional[Quantity] = None,  # The ball's Poisson ratio ν in K_HZ (Eq 2), instead of its material's (with --sphere); 0 to 0.5
    no_tension: Optional[bool] = None,  # Clamp the contact force at ≥ 0 (a contact cannot pull)
    duration: Optional[Quantity] = None,  # Simulated time (s); 1e-6 to 1e6 s
    solver: Optional[Solver] = None,  # Solver
    dt: Optional[Quantity] = None,  # Newmark time step (s) [default: 1e-7]; 1e-14 to 0.001 s
    density: Optional[Quantity] = None,  # Ball density (kg/m³) [default: the --sphere material's]: with --mass the radius follows, with --radius the mass; 10 to 25000 kg/m^3
    radius: Optional[Quantity] = None,  # Ball radius (m): with --mass as given, else the mass follows from the density; 0.0001 to 2 m
    r: Optional[Quantity] = None,  # Observer distance (m); 0.001 to 1000 m
    theta: Optional[Quantity] = None,  # Observer angle (degrees); -180 to 180 deg
    source: Optional[Source] = None,  # Reflecting surfaces around the impact
    quad_signs: Optional[QuadSigns] = None,  # Quadrupole wall-image signs
    pulse: Optional[PulseShape] = None,  # Acceleration pulse of each impact's sound: half-sine (Eq 7) or the exact Hertz pulse
    model: Optional[Model] = None,  # The model of the world [default: paper]: physical is the level a microphone reads (peak, real air, materials)
    air_temperature: Optional[Quantity] = None,  # Air temperature (°C) of the physical model: ρ0 and c follow [default: 20]; -60 to 60 degC
    air_pressure: Optional[Quantity] = None,  # Air pressure (Pa, or e.g. 101.325kPa) of the physical model: ρ0 follows [default: 101325]; 20000 to 2e5 Pa
    l_star: Optional[Quantity] = None,  # Zone threshold L* on SPLmax (dB); 0 to 200 dB
    e_star: Optional[Quantity] = None,  # Zone threshold e* on the damping inclination (cm/s); 0 to 1000 cm/s
    force: Optional[Quantity] = None,  # Amplitude F0 of a harmonic force F0·cos(2π·f·t) on the main mass (N, or e.g. 2N) [default: 0, the paper's free decay]; needs --freq; 0 to 1e6 N (alias force_amplitude)
    freq: Optional[Quantity] = None,  # Frequency f of the harmonic force (Hz, or e.g. 5Hz); 0.001 to 1e5 Hz
    ball_position: Optional[Quantity] = None,  # The ball's initial offset y0 from the enclosure's centre (m, or e.g. -1cm; |y0| < d/2) [default: 0, centred]; -5 to 5 m
    ball_velocity: Optional[Quantity] = None,  # The ball's initial velocity w0 (m/s) [default: 0]; -100 to 100 m/s
    periods: Optional[Count] = None,  # Forcing periods N of the steady-state window of a forced run [default: 10]; 1 to 1000 periods
    settle: Optional[bool] = None,  # Run a forced run on past --duration, N periods at a time, until its steady amplitude settles
    no_limit: bool = False,
) -> Restitution:
    """R of one isolated contact at ``u0`` against the impact mass, as ``thud restitution``;
    with ``target`` also the c1 that gives it."""

def axis(name: Literal["masses", "gaps"], spec: str) -> FloatArray:
    """The values of a sweep axis "FROM:TO:N" exactly as the command line computes them:
    axis("masses", "30g:100g:20") (kg), axis("gaps", "2cm:5cm:20") (m)."""

def schema() -> Dict[str, List[Tuple[str, str, str]]]:
    """The one data schema: {table: [(name, unit, meaning), …]}, the columns in order."""

def presets() -> Dict[str, str]:
    """The named starting designs (``preset=``) with their one-line descriptions."""

def ranges() -> List[Dict[str, object]]:
    """The valid range of every numeric parameter (``thud limits``): dicts with param (the
    keyword), what, min, max, unit (of a plain number) and reason."""

class LimitRange(TypedDict):
    """A parameter's range in ``limits()["ranges"]``: param as the command line's flag."""
    max: float
    min: float
    param: str
    reason: str
    unit: str
    what: str

class LimitCap(TypedDict):
    """A work cap in ``limits()["caps"]`` and ``["solver_caps"]``."""
    basis: str
    max: float
    what: str

class Limits(TypedDict):
    """``thud limits --json``, key for key."""
    caps: List[LimitCap]
    orbit_seed_impacts_max: int
    orbit_transient_periods_max: int
    ranges: List[LimitRange]
    settle_periods_max: int
    solver_caps: List[LimitCap]

class PaperColumn(TypedDict):
    """A column of a paper table: its key in each row, its heading as printed."""
    key: str
    label: str

class PaperTable(TypedDict, total=False):
    """A table or figure of the paper, as ``thud paper ID --json`` (``summary`` only for some)."""
    id: str
    title: str
    notes: List[str]
    columns: List[PaperColumn]
    rows: List[Dict[str, Any]]
    summary: Dict[str, Dict[str, Any]]

def paper(id: str) -> PaperTable:
    """A table or figure of the paper reproduced beside the paper's numbers: the dict of
    ``thud paper ID --json``, key for key; an unknown id raises ParameterError."""

def paper_ids() -> List[str]:
    """The ids of the paper's tables and figures (``thud paper --list``): table1 … fig17."""

def limits() -> Limits:
    """Every parameter's range and every work cap: the table of ``thud limits --json``, key for
    key (a range's param is the flag without its dashes; ``ranges()`` gives the keywords)."""


class StructureFit(Dict[str, Any]):
    """The structure's fit, a dict of ``thud fit structure --json``'s keys (``thud.fit_structure``)."""

    def as_dict(self, json: bool = False) -> Dict[str, Any]: ...
    def to_dataframe(self) -> Any:
        """One row, the ``--json`` keys as columns. Needs pandas."""
    def to_xarray(self) -> Any:
        """The fitted values as 0-d variables, the rest in attrs. Needs xarray."""

class DamperFit(Dict[str, Any]):
    """The damper's fit, a dict of ``thud fit damper --json``'s keys (``thud.fit_damper``)."""

    def as_dict(self, json: bool = False) -> Dict[str, Any]: ...
    def to_dataframe(self) -> Any:
        """The measured and model envelopes, one row a period (t_s); the numbers in attrs. Needs pandas."""
    def to_xarray(self) -> Any:
        """The envelopes on t_s, c1 and restitution with their intervals. Needs xarray."""

def fit_structure(
    t_s: Union[Sequence[float], npt.ArrayLike],
    x: Union[Sequence[float], npt.ArrayLike],
    *,
    main_mass: Quantity,
    quantity: Literal["x", "v", "a"] = "x",
) -> StructureFit:
    """The structure alone, struck once: f_n, ζ, K and C with standard errors from a measured
    free decay, as ``thud fit structure --json`` (keys f_n_hz, zeta, k_n_m, c_n_s_m, each with
    ``_stderr``, residual_rms, converged)."""

def fit_damper(
    t_s: Union[Sequence[float], npt.ArrayLike, Sequence[Sequence[float]]],
    x: Union[Sequence[float], npt.ArrayLike, Sequence[Sequence[float]]],
    *,
    preset: Optional[str] = None,
    design: Union[str, "os.PathLike[str]", None] = None,  # A design file (what --save, fit --save and the explorer write) or a saved design's name, instead of preset
    mass: Optional[Quantity] = None,  # Impact mass m (kg, or e.g. 40.5g); 0.0001 to 100 kg
    gap: Optional[Quantity] = None,  # Total clearance d (m, or e.g. 4cm); 1e-5 to 10 m
    v0: Optional[Quantity] = None,  # Initial velocity of the main mass (m/s); -100 to 100 m/s
    main_mass: Optional[Quantity] = None,  # Main mass M (kg); 0.001 to 1e6 kg
    k: Optional[Quantity] = None,  # Spring stiffness K (N/m); 0 to 1e10 N/m
    c: Optional[Quantity] = None,  # Viscous damping C (N·s/m); 0 to 1e6 N·s/m
    c1: Optional[Quantity] = None,  # Contact damping c1 (N·s/m); 0 to 1e6 N·s/m
    k_hz: Optional[Quantity] = None,  # Hertz stiffness K_HZ (N/m^1.5); 10000 to 1e13 N/m^1.5
    sphere: Optional[str] = None,  # Ball material: K_HZ then follows from the materials and the ball's radius (Eq 2)
    plate: Optional[str] = None,  # Enclosure material (with --sphere) [default: steel]
    sphere_poisson: Optional[Quantity] = None,  # The ball's Poisson ratio ν in K_HZ (Eq 2), instead of its material's (with --sphere); 0 to 0.5
    no_tension: Optional[bool] = None,  # Clamp the contact force at ≥ 0 (a contact cannot pull)
    duration: Optional[Quantity] = None,  # Simulated time (s); 1e-6 to 1e6 s
    solver: Optional[Solver] = None,  # Solver
    dt: Optional[Quantity] = None,  # Newmark time step (s) [default: 1e-7]; 1e-14 to 0.001 s
    density: Optional[Quantity] = None,  # Ball density (kg/m³): the radius follows from the mass; 10 to 25000 kg/m^3
    radius: Optional[Quantity] = None,  # Ball radius (m), whatever the mass; 0.0001 to 2 m
    r: Optional[Quantity] = None,  # Observer distance (m); 0.001 to 1000 m
    theta: Optional[Quantity] = None,  # Observer angle (degrees); -180 to 180 deg
    source: Optional[Source] = None,  # Reflecting surfaces around the impact
    quad_signs: Optional[QuadSigns] = None,  # Quadrupole wall-image signs
    pulse: Optional[PulseShape] = None,  # Acceleration pulse of each impact's sound: half-sine (Eq 7) or the exact Hertz pulse
    l_star: Optional[Quantity] = None,  # Zone threshold L* on SPLmax (dB); 0 to 200 dB
    e_star: Optional[Quantity] = None,  # Zone threshold e* on the damping inclination (cm/s); 0 to 1000 cm/s
    force: Optional[Quantity] = None,  # Amplitude F0 of a harmonic force F0·cos(2π·f·t) on the main mass (N, or e.g. 2N) [default: 0, the paper's free decay]; needs --freq; 0 to 1e6 N (alias force_amplitude)
    freq: Optional[Quantity] = None,  # Frequency f of the harmonic force (Hz, or e.g. 5Hz); 0.001 to 1e5 Hz
    ball_velocity: Optional[Quantity] = None,  # The ball's initial velocity w0 (m/s) [default: 0]; -100 to 100 m/s
    periods: Optional[Count] = None,  # Forcing periods N of the steady-state window of a forced run [default: 10]; 1 to 1000 periods
    settle: Optional[bool] = None,  # Run a forced run on past --duration, N periods at a time, until its steady amplitude settles
    quantity: Literal["x", "v", "a"] = "x",
    no_limit: bool = False,
) -> DamperFit:
    """The structure with the damper, struck once at the record's start, every other parameter
    known: c1 and its restitution with 95 % intervals, as ``thud fit damper --json`` (keys
    c1_n_s_m, c1_n_s_m_stderr, c1_n_s_m_ci, restitution, restitution_stderr, residual_rms,
    and note where c1 is poorly bounded).
    ``t_s`` and ``x`` may be lists of records (repeated strikes), fitted together."""


# ---- The design search (thud design): design(), Front, Designer ----

from typing import Mapping

#: A value of one design variable: a number in the row's plain unit (an int for a count) or a
#: name; a point is handed out as keywords (Any, so it spreads into ``simulate(**x)``).
DesignValue = Any
#: One text in the command line's words, or a list of them ("mass=20g:120g").
Texts = Union[str, Sequence[str], None]

class Front:
    """The Pareto front of a design search (``thud.design``; ``thud design --json``): every
    non-dominated design with its variables, objectives and constraint margins, and the
    search's budget, seed, reference point and hypervolume."""
    design: Dict[str, Any]
    variables: List[Dict[str, Any]]
    objectives: List[Dict[str, Any]]
    constraints: List[str]
    band_hz: List[float]
    evaluations: int
    budget: int
    seed: int
    partial: bool
    reference: Optional[List[float]]
    hypervolume: Optional[float]
    binding: Optional[str]
    @property
    def designs(self) -> List[Dict[str, Any]]:
        """The front designs: index, variables, objectives and margins, each a dict by column."""
    def keywords(self, k: int) -> Dict[str, DesignValue]:
        """The k-th front design's variables as keywords, for ``thud.simulate(**base, **kw)``."""
    def to_dataframe(self) -> Any:
        """One row per front design: index, variables, objectives, margins (``--csv``'s columns)."""
    def to_xarray(self) -> Any:
        """The front on the dimension design; the search in attrs."""
    def as_dict(self, json: bool = False) -> Dict[str, Any]:
        """The command line's ``thud design --json`` record."""
    def __len__(self) -> int: ...

def design(
    *,
    preset: Optional[str] = None,
    design: Union[str, "os.PathLike[str]", None] = None,  # A design file (what --save, fit --save and the explorer write) or a saved design's name, instead of preset
    mass: Optional[Quantity] = None,  # Impact mass m (kg, or e.g. 40.5g); 0.0001 to 100 kg
    gap: Optional[Quantity] = None,  # Total clearance d (m, or e.g. 4cm); 1e-5 to 10 m
    v0: Optional[Quantity] = None,  # Initial velocity of the main mass (m/s); -100 to 100 m/s
    main_mass: Optional[Quantity] = None,  # Main mass M (kg); 0.001 to 1e6 kg
    k: Optional[Quantity] = None,  # Spring stiffness K (N/m); 0 to 1e10 N/m
    c: Optional[Quantity] = None,  # Viscous damping C (N·s/m); 0 to 1e6 N·s/m
    c1: Optional[Quantity] = None,  # Contact damping c1 (N·s/m); 0 to 1e6 N·s/m
    k_hz: Optional[Quantity] = None,  # Hertz stiffness K_HZ (N/m^1.5); 10000 to 1e13 N/m^1.5
    sphere: Optional[str] = None,  # Ball material: K_HZ then follows from the materials and the ball's radius (Eq 2)
    plate: Optional[str] = None,  # Enclosure material (with --sphere) [default: steel]
    sphere_poisson: Optional[Quantity] = None,  # The ball's Poisson ratio ν in K_HZ (Eq 2), instead of its material's (with --sphere); 0 to 0.5
    no_tension: Optional[bool] = None,  # Clamp the contact force at ≥ 0 (a contact cannot pull)
    duration: Optional[Quantity] = None,  # Simulated time (s); 1e-6 to 1e6 s
    solver: Optional[Solver] = None,  # Solver
    dt: Optional[Quantity] = None,  # Newmark time step (s) [default: 1e-7]; 1e-14 to 0.001 s
    density: Optional[Quantity] = None,  # Ball density (kg/m³) [default: the --sphere material's]: with --mass the radius follows, with --radius the mass; 10 to 25000 kg/m^3
    radius: Optional[Quantity] = None,  # Ball radius (m): with --mass as given, else the mass follows from the density; 0.0001 to 2 m
    r: Optional[Quantity] = None,  # Observer distance (m); 0.001 to 1000 m
    theta: Optional[Quantity] = None,  # Observer angle (degrees); -180 to 180 deg
    source: Optional[Source] = None,  # Reflecting surfaces around the impact
    quad_signs: Optional[QuadSigns] = None,  # Quadrupole wall-image signs
    pulse: Optional[PulseShape] = None,  # Acceleration pulse of each impact's sound: half-sine (Eq 7) or the exact Hertz pulse
    model: Optional[Model] = None,  # The model of the world [default: paper]: physical is the level a microphone reads (peak, real air, materials)
    air_temperature: Optional[Quantity] = None,  # Air temperature (°C) of the physical model: ρ0 and c follow [default: 20]; -60 to 60 degC
    air_pressure: Optional[Quantity] = None,  # Air pressure (Pa, or e.g. 101.325kPa) of the physical model: ρ0 follows [default: 101325]; 20000 to 2e5 Pa
    rho_c: Optional[Quantity] = None,  # Air impedance ρ0·c of the paper model (Pa·s/m) [default: 400, the paper's]; 1 to 1e7 Pa·s/m
    sound_speed: Optional[Quantity] = None,  # Speed of sound c of the paper model (m/s) [default: 343]; 1 to 10000 m/s
    l_star: Optional[Quantity] = None,  # Zone threshold L* on SPLmax (dB); 0 to 200 dB
    e_star: Optional[Quantity] = None,  # Zone threshold e* on the damping inclination (cm/s); 0 to 1000 cm/s
    force: Optional[Quantity] = None,  # Amplitude F0 of a harmonic force F0·cos(2π·f·t) on the main mass (N, or e.g. 2N) [default: 0, the paper's free decay]; needs --freq; 0 to 1e6 N (alias force_amplitude)
    freq: Optional[Quantity] = None,  # Frequency f of the harmonic force (Hz, or e.g. 5Hz); 0.001 to 1e5 Hz
    ball_position: Optional[Quantity] = None,  # The ball's initial offset y0 from the enclosure's centre (m, or e.g. -1cm; |y0| < d/2) [default: 0, centred]; -5 to 5 m
    ball_velocity: Optional[Quantity] = None,  # The ball's initial velocity w0 (m/s) [default: 0]; -100 to 100 m/s
    periods: Optional[Count] = None,  # Forcing periods N of the steady-state window of a forced run [default: 10]; 1 to 1000 periods
    settle: Optional[bool] = None,  # Run a forced run on past --duration, N periods at a time, until its steady amplitude settles
    vary: Texts = None,
    choose: Texts = None,
    minimize: Texts = None,
    maximize: Texts = None,
    require: Texts = None,
    over: Optional[str] = None,
    evaluations: Union[int, str] = 400,
    seed: int = 0,
    reference: Optional[Sequence[float]] = None,
    no_limit: bool = False,
    progress: ProgressArg = None,
) -> Front:
    """The best dampers within the user's limits, as a Pareto front (``thud design``). Ctrl-C
    raises KeyboardInterrupt whose ``front`` is the front found so far, marked partial."""

class Designer:
    """The design search in ask/tell form: ask for points, evaluate them anywhere, tell the
    results back, until ``done``; ``result()`` is the Front."""
    def __init__(
        self,
        *,
        preset: Optional[str] = None,
        design: Union[str, "os.PathLike[str]", None] = None,  # A design file (what --save, fit --save and the explorer write) or a saved design's name, instead of preset
        mass: Optional[Quantity] = None,  # Impact mass m (kg, or e.g. 40.5g); 0.0001 to 100 kg
        gap: Optional[Quantity] = None,  # Total clearance d (m, or e.g. 4cm); 1e-5 to 10 m
        v0: Optional[Quantity] = None,  # Initial velocity of the main mass (m/s); -100 to 100 m/s
        main_mass: Optional[Quantity] = None,  # Main mass M (kg); 0.001 to 1e6 kg
        k: Optional[Quantity] = None,  # Spring stiffness K (N/m); 0 to 1e10 N/m
        c: Optional[Quantity] = None,  # Viscous damping C (N·s/m); 0 to 1e6 N·s/m
        c1: Optional[Quantity] = None,  # Contact damping c1 (N·s/m); 0 to 1e6 N·s/m
        k_hz: Optional[Quantity] = None,  # Hertz stiffness K_HZ (N/m^1.5); 10000 to 1e13 N/m^1.5
        sphere: Optional[str] = None,  # Ball material: K_HZ then follows from the materials and the ball's radius (Eq 2)
        plate: Optional[str] = None,  # Enclosure material (with --sphere) [default: steel]
        sphere_poisson: Optional[Quantity] = None,  # The ball's Poisson ratio ν in K_HZ (Eq 2), instead of its material's (with --sphere); 0 to 0.5
        no_tension: Optional[bool] = None,  # Clamp the contact force at ≥ 0 (a contact cannot pull)
        duration: Optional[Quantity] = None,  # Simulated time (s); 1e-6 to 1e6 s
        solver: Optional[Solver] = None,  # Solver
        dt: Optional[Quantity] = None,  # Newmark time step (s) [default: 1e-7]; 1e-14 to 0.001 s
        density: Optional[Quantity] = None,  # Ball density (kg/m³) [default: the --sphere material's]: with --mass the radius follows, with --radius the mass; 10 to 25000 kg/m^3
        radius: Optional[Quantity] = None,  # Ball radius (m): with --mass as given, else the mass follows from the density; 0.0001 to 2 m
        r: Optional[Quantity] = None,  # Observer distance (m); 0.001 to 1000 m
        theta: Optional[Quantity] = None,  # Observer angle (degrees); -180 to 180 deg
        source: Optional[Source] = None,  # Reflecting surfaces around the impact
        quad_signs: Optional[QuadSigns] = None,  # Quadrupole wall-image signs
        pulse: Optional[PulseShape] = None,  # Acceleration pulse of each impact's sound: half-sine (Eq 7) or the exact Hertz pulse
        model: Optional[Model] = None,  # The model of the world [default: paper]: physical is the level a microphone reads (peak, real air, materials)
        air_temperature: Optional[Quantity] = None,  # Air temperature (°C) of the physical model: ρ0 and c follow [default: 20]; -60 to 60 degC
        air_pressure: Optional[Quantity] = None,  # Air pressure (Pa, or e.g. 101.325kPa) of the physical model: ρ0 follows [default: 101325]; 20000 to 2e5 Pa
        rho_c: Optional[Quantity] = None,  # Air impedance ρ0·c of the paper model (Pa·s/m) [default: 400, the paper's]; 1 to 1e7 Pa·s/m
        sound_speed: Optional[Quantity] = None,  # Speed of sound c of the paper model (m/s) [default: 343]; 1 to 10000 m/s
        l_star: Optional[Quantity] = None,  # Zone threshold L* on SPLmax (dB); 0 to 200 dB
        e_star: Optional[Quantity] = None,  # Zone threshold e* on the damping inclination (cm/s); 0 to 1000 cm/s
        force: Optional[Quantity] = None,  # Amplitude F0 of a harmonic force F0·cos(2π·f·t) on the main mass (N, or e.g. 2N) [default: 0, the paper's free decay]; needs --freq; 0 to 1e6 N (alias force_amplitude)
        freq: Optional[Quantity] = None,  # Frequency f of the harmonic force (Hz, or e.g. 5Hz); 0.001 to 1e5 Hz
        ball_position: Optional[Quantity] = None,  # The ball's initial offset y0 from the enclosure's centre (m, or e.g. -1cm; |y0| < d/2) [default: 0, centred]; -5 to 5 m
        ball_velocity: Optional[Quantity] = None,  # The ball's initial velocity w0 (m/s) [default: 0]; -100 to 100 m/s
        periods: Optional[Count] = None,  # Forcing periods N of the steady-state window of a forced run [default: 10]; 1 to 1000 periods
        settle: Optional[bool] = None,  # Run a forced run on past --duration, N periods at a time, until its steady amplitude settles
        vary: Texts = None,
        choose: Texts = None,
        minimize: Texts = None,
        maximize: Texts = None,
        require: Texts = None,
        over: Optional[str] = None,
        evaluations: Union[int, str] = 400,
        seed: int = 0,
        reference: Optional[Sequence[float]] = None,
        no_limit: bool = False,
    ) -> None: ...
    @property
    def base(self) -> Dict[str, Any]:
        """The base design's keywords, to run a point with: ``thud.simulate(**d.base, **x)``."""
    @property
    def band_hz(self) -> List[float]:
        """The forcing frequencies of the band (Hz), one run of each point per frequency."""
    def runs(self, x: Mapping[str, DesignValue]) -> List[Dict[str, Any]]:
        """The keywords of each run of a point, for ``thud.simulate(**kw)`` (one per band frequency)."""
    @property
    def columns(self) -> List[str]:
        """The result columns a told result carries."""
    @property
    def done(self) -> bool:
        """Whether the search is over."""
    @property
    def outstanding(self) -> int:
        """Points asked and not told yet."""
    def ask(self, n: int = 1) -> List[Dict[str, DesignValue]]:
        """Up to n points to evaluate, each the variables as keywords."""
    def tell(
        self,
        xs: Sequence[Mapping[str, DesignValue]],
        results: Sequence[
            Union[
                Run,
                Mapping[str, Optional[float]],
                str,
                BaseException,
                Sequence[Union[Run, Mapping[str, Optional[float]]]],
            ]
        ],
    ) -> None:
        """What each point gave: a Run, a dict by column, or why it could not be run; with a
        band, a list of those, one per frequency of band_hz."""
    def result(self) -> Front:
        """The front of every design told so far (partial until done)."""
