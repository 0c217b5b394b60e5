# SPDX-License-Identifier: BSD-3-Clause
"""Python binding of the ladrc C library (ctypes on the shared library).

    import ladrc
    axis = ladrc.Axis({"variant": "LADRC", "dt_s": 1e-3, "inertia_kg_m2": 5.445e-3,
                       "u_min_Nm": -0.05, "u_max_Nm": 0.05})
    u = axis.step(ref_rad, angle_rad)            # one tick, returns the torque (N m)
    axis.set_applied(u)

The library is found through the LADRC_LIBRARY environment variable (path of
libladrc.so), else next to this package (where pip install puts the one it
builds), else on the system's library path; ladrc.load(path) picks one
explicitly. A library built with LADRC_REAL_DOUBLE
works too: the real type is asked from the library.

Configs are dicts: the keys are the C config's field names (ladrc/axis.h,
ladrc/attitude.h, ladrc/mixer.h), enums may be given by name ("HP_MLADRC",
"LEVANT", "ONLINE"). An init that fails raises LadrcError with the library's
status text. The C structs are mirrored here and checked against the sizes
the library reports (ladrc_sizeof_*): a mismatch raises LadrcLayoutError
at load time instead of passing garbage.
"""
import ctypes
import ctypes.util
import os

import numpy as np

try:
    from ._version import __version__  # written by setup.py into the installed package
except ImportError:  # a source checkout on PYTHONPATH: the CMake project's version
    from . import _project_version

    __version__ = _project_version.read(
        os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "CMakeLists.txt"))

__all__ = ["__version__", "Axis", "Attitude", "Mixer", "MixerOutput", "LadrcError", "LadrcLayoutError",
           "load", "library", "status_str", "FAULT_INPUT", "FAULT_RATE", "FAULT_APPLIED",
           "FAULT_STATE"]

FAULT_INPUT = 1
FAULT_RATE = 2
FAULT_APPLIED = 4
FAULT_STATE = 8

ENUMS = {
    "variant": {"LADRC": 0, "LP_MLADRC": 1, "HP_MLADRC": 2, "PID": 3, "CASCADED": 4, "INDI": 5,
                "RATE_ADRC": 6},
    "shaper": {"TD": 0, "NONE": 1, "LEVANT": 2},
    "leso_method": {"ZOH": 0, "EULER": 1},
    "levant_method": {"IMPLICIT": 0, "HD": 1, "EULER": 2},
    "hp_freq_mode": {"KNOWN": 0, "ONLINE": 1},
    "hp_sample": {"OBSERVER": 0, "GYRO": 1},
    "mode": {"SATURATE": 0, "IDEAL": 1},
}

# Functions whose symbol carries the real type (ladrc/types.h, ABI guard).
_ABI_NAMED = {"ladrc_attitude_config_default", "ladrc_attitude_init", "ladrc_axis_config_default",
              "ladrc_axis_init", "ladrc_mixer_init"}
# Those that carry the variant and shaper set as well (ladrc/types.h, ABI guard).
_ABI_SET_NAMED = {"ladrc_attitude_config_default", "ladrc_attitude_init", "ladrc_axis_config_default",
                  "ladrc_axis_init"}


class LadrcError(Exception):
    """An init refused its config: status code, the library's text, and for
    the attitude controller the axis (0 roll, 1 pitch, 2 yaw) or -1."""

    def __init__(self, status, text, axis=-1):
        self.status = status
        self.text = text
        self.axis = axis
        where = f" (axis {axis})" if axis >= 0 else ""
        super().__init__(f"{text}{where}")


class LadrcLayoutError(RuntimeError):
    """The Python mirror of a C struct does not match the library's."""


_ENUM_PREFIXES = {"variant": "LADRC_VARIANT_", "shaper": "LADRC_SHAPER_", "leso_method": "LADRC_LESO_",
                  "levant_method": "LADRC_LEVANT_", "hp_freq_mode": "LADRC_HP_FREQ_",
                  "hp_sample": "LADRC_HP_SAMPLE_", "mode": "LADRC_MIXER_"}


def _enum_value(field, value):
    """An enum field's value from its C name, with or without the prefix
    ("HP_MLADRC" or "LADRC_VARIANT_HP_MLADRC"), or from its number."""
    if isinstance(value, str):
        names = ENUMS[field]
        key = value.upper()
        if key.startswith(_ENUM_PREFIXES[field]):
            key = key[len(_ENUM_PREFIXES[field]):]
        if key not in names:
            raise ValueError(f"{field}: '{value}' is not one of {sorted(names)}")
        return names[key]
    return int(value)


class _Library:
    def __init__(self, path):
        self.path = path
        self.dll = ctypes.CDLL(path)
        fn = self.dll.ladrc_sizeof_real
        fn.restype = ctypes.c_size_t
        fn.argtypes = []
        size = fn()
        if size == 4:
            self.real, self.dtype, suffix = ctypes.c_float, np.float32, "_float"
        elif size == 8:
            self.real, self.dtype, suffix = ctypes.c_double, np.float64, "_double"
        else:
            raise LadrcLayoutError(f"{path}: sizeof(ladrc_real_t) = {size}")
        self._suffix = suffix
        fn = self.dll.ladrc_abi_set
        fn.restype = ctypes.c_char_p
        fn.argtypes = []
        self._set_suffix = suffix + fn().decode()
        fn = self.dll.ladrc_hp_max_tones
        fn.restype = ctypes.c_size_t
        fn.argtypes = []
        self.hp_max_tones = fn()
        self._structs()
        self._check_sizes()
        self._prototypes()

    def _structs(self):
        r = self.real
        i = ctypes.c_int  # C enums: int on the ABIs this binding supports (checked by size)
        u16 = ctypes.c_uint16
        u8 = ctypes.c_uint8
        tones = self.hp_max_tones  # LADRC_HP_MAX_TONES as the library was built

        class AxisConfig(ctypes.Structure):
            _fields_ = [("variant", i), ("dt_s", r), ("u_min_Nm", r), ("u_max_Nm", r),
                        ("angle_limit_rad", r), ("rate_limit_rad_s", r), ("applied_limit_Nm", r),
                        ("wc_rad_s", r), ("wo_rad_s", r), ("b0", r), ("leso_method", i),
                        ("shaper", i), ("td_accel_rad_s2", r), ("td_h0_s", r),
                        ("levant_method", i), ("levant_lipschitz_rad_s4", r),
                        ("pid_kp", r), ("pid_ki", r), ("pid_kd", r), ("pid_d_filter_tau_s", r),
                        ("pid_i_limit_Nm", r), ("lp_lambda0_per_s", r), ("lp_k0_per_s", r),
                        ("hp_freq_mode", i), ("hp_n_tones", u8), ("hp_freq_rad_s", r * tones),
                        ("hp_freq_min_rad_s", r), ("hp_freq_max_rad_s", r), ("hp_lambda0_per_s", r),
                        ("hp_freq_lambda0_per_s", r), ("hp_freq_filter_rad_s", r),
                        ("hp_fit_decimation", u16), ("hp_sample", i),
                        ("motor_tau_s", r), ("delay_ticks", u16), ("wrap_angle", u8),
                        ("indi_att_kp_per_s", r), ("indi_rate_kp_per_s", r), ("indi_filter_rad_s", r),
                        ("cas_att_kp", r), ("cas_rate_max_rad_s", r), ("cas_rate_kp", r),
                        ("cas_rate_ki", r), ("cas_rate_kd", r), ("cas_d_filter_tau_s", r),
                        ("cas_i_limit_Nm", r), ("cas_rate_filter_tau_s", r),
                        ("radrc_kp_per_s", r), ("radrc_att_kp_per_s", r), ("radrc_rate_max_rad_s", r),
                        ("radrc_acro", u8),
                        ("cas_i_relax_rad_s", r), ("cas_rate_ff", r), ("cas_setpoint_ff", u8),
                        ("indi_adapt", u8), ("indi_adapt_mu", r), ("indi_adapt_jerk_min_rad_s3", r),
                        ("indi_adapt_min_ratio", r), ("indi_adapt_max_ratio", r)]

        class AttitudeConfig(ctypes.Structure):
            _fields_ = [("axis", AxisConfig * 3), ("inertia_kg_m2", r * 3), ("drag_Nms", r),
                        ("coupling_feed", u8), ("frame", i), ("yaw_weight", r), ("spool_up_s", r),
                        ("gain_thrust_curve", r), ("gain_full_thrust_N", r), ("gain_ref_thrust_N", r),
                        ("gain_ref_voltage_V", r)]

        class MixerConfig(ctypes.Structure):
            _fields_ = [("kL_N_s2", r), ("arm_m", r), ("b_Nm_s2", r), ("mass_kg", r),
                        ("g_m_s2", r), ("w2_min_rad2_s2", r), ("w2_max_rad2_s2", r),
                        ("tilt_max_rad", r), ("mode", i)]

        class MixerOutputC(ctypes.Structure):
            _fields_ = [("w2_rad2_s2", r * 4), ("w_rad_s", r * 4), ("thrust_N", r),
                        ("torque_Nm", r * 3), ("saturated", u8), ("faults", u8)]

        self.AxisConfig = AxisConfig
        self.AttitudeConfig = AttitudeConfig
        self.MixerConfig = MixerConfig
        self.MixerOutputC = MixerOutputC

    def _check_sizes(self):
        mirrors = {"axis_config_t": self.AxisConfig, "attitude_config_t": self.AttitudeConfig,
                   "mixer_config_t": self.MixerConfig, "mixer_output_t": self.MixerOutputC}
        for name, struct in mirrors.items():
            c = self.sizeof(name)
            if c != ctypes.sizeof(struct):
                raise LadrcLayoutError(
                    f"{self.path}: sizeof(ladrc_{name}) is {c} in the library, {ctypes.sizeof(struct)} "
                    "in the Python mirror: the binding does not match this library version")

    def sizeof(self, name):
        fn = getattr(self.dll, f"ladrc_sizeof_{name}")
        fn.restype = ctypes.c_size_t
        fn.argtypes = []
        return fn()

    def fn(self, name, restype, *argtypes):
        if name in _ABI_SET_NAMED:
            name += self._set_suffix
        elif name in _ABI_NAMED:
            name += self._suffix
        f = getattr(self.dll, name)
        f.restype = restype
        f.argtypes = list(argtypes)
        return f

    def _prototypes(self):
        r, vp, i = self.real, ctypes.c_void_p, ctypes.c_int
        rp = ctypes.POINTER(r)
        u8 = ctypes.c_uint8
        self.status_str = self.fn("ladrc_status_str", ctypes.c_char_p, i)
        self.axis_config_default = self.fn("ladrc_axis_config_default", None,
                                           ctypes.POINTER(self.AxisConfig), i, r, r)
        self.axis_init = self.fn("ladrc_axis_init", i, vp, ctypes.POINTER(self.AxisConfig))
        self.axis_reset = self.fn("ladrc_axis_reset", None, vp, r)
        self.axis_step = self.fn("ladrc_axis_step", u8, vp, r, r, rp, rp)
        self.axis_set_applied = self.fn("ladrc_axis_set_applied", None, vp, r)
        self.axis_get_faults = self.fn("ladrc_axis_get_faults", u8, vp)
        self.axis_get_consecutive_faults = self.fn("ladrc_axis_get_consecutive_faults", ctypes.c_uint32, vp)
        self.axis_get_estimate = self.fn("ladrc_axis_get_estimate", None, vp, rp, rp, rp)
        self.attitude_config_default = self.fn("ladrc_attitude_config_default", None,
                                               ctypes.POINTER(self.AttitudeConfig), i, r, rp, r)
        self.attitude_init = self.fn("ladrc_attitude_init", i, vp, ctypes.POINTER(self.AttitudeConfig),
                                     ctypes.POINTER(i))
        self.attitude_reset = self.fn("ladrc_attitude_reset", None, vp, rp)
        self.attitude_step = self.fn("ladrc_attitude_step", u8, vp, rp, rp, rp, rp)
        self.attitude_set_applied = self.fn("ladrc_attitude_set_applied", None, vp, rp)
        self.mixer_init = self.fn("ladrc_mixer_init", i, vp, ctypes.POINTER(self.MixerConfig))
        self.mixer_reset = self.fn("ladrc_mixer_reset", None, vp)
        self.mixer_thrust_from_tilt = self.fn("ladrc_mixer_thrust_from_tilt", r, vp, r, r)
        self.mixer_step = self.fn("ladrc_mixer_step", u8, vp, r, rp, ctypes.POINTER(self.MixerOutputC))

    def state(self, name):
        """Zeroed storage for a state struct, sized by the library (8-byte aligned,
        the largest alignment of the C structs)."""
        return (ctypes.c_uint64 * ((self.sizeof(name) + 7) // 8))()

    def array(self, values, n, what):
        a = np.ascontiguousarray(values, dtype=self.dtype)
        if a.shape != (n,):
            raise ValueError(f"{what}: expected {n} values, got shape {a.shape}")
        return a


_library = None


def _default_path():
    env = os.environ.get("LADRC_LIBRARY")
    if env:
        return env
    here = os.path.dirname(os.path.abspath(__file__))
    for name in ("libladrc.so", "libladrc.dylib", "ladrc.dll"):
        if os.path.exists(os.path.join(here, name)):
            return os.path.join(here, name)
    found = ctypes.util.find_library("ladrc")
    if found:
        return found
    raise OSError("libladrc not found: build it with -DBUILD_SHARED_LIBS=ON and set LADRC_LIBRARY "
                  "to the path of libladrc.so")


def load(path=None):
    """Loads the shared library (path, or the default search) and returns it."""
    global _library
    _library = _Library(path or _default_path())
    return _library


def library():
    return _library if _library is not None else load()


def status_str(status):
    """The library's text of a status code."""
    return library().status_str(int(status)).decode()


def _check(lib, status, axis=-1):
    if status != 0:
        raise LadrcError(status, lib.status_str(status).decode(), axis)


def _apply(struct, overrides, what):
    fields = dict(struct._fields_)
    for key, value in overrides.items():
        if key not in fields:
            raise KeyError(f"{what}: no field '{key}' (fields: {', '.join(fields)})")
        if issubclass(fields[key], ctypes.Array):
            array = getattr(struct, key)
            if len(value) > len(array):
                raise ValueError(f"{what}: {key} takes at most {len(array)} values")
            for k, v in enumerate(value):
                array[k] = v
        else:
            setattr(struct, key, _enum_value(key, value) if key in ENUMS else value)


def _axis_config(lib, variant, dt_s, inertia, overrides):
    cfg = lib.AxisConfig()
    lib.axis_config_default(ctypes.byref(cfg), _enum_value("variant", variant), dt_s, inertia)
    _apply(cfg, overrides, "axis config")
    return cfg


def _real_ptr(lib, a):
    return a.ctypes.data_as(ctypes.POINTER(lib.real))


class Axis:
    """One axis (ladrc_axis_t). config: dict with "variant", "dt_s",
    "inertia_kg_m2" (for ladrc_axis_config_default) and any field of
    ladrc_axis_config_t to override."""

    def __init__(self, config):
        lib = self._lib = library()
        config = dict(config)
        try:
            variant, dt_s, inertia = (config.pop(k) for k in ("variant", "dt_s", "inertia_kg_m2"))
        except KeyError as e:
            raise KeyError(f"axis config needs {e}") from None
        self.config = _axis_config(lib, variant, dt_s, inertia, config)
        self._state = lib.state("axis_t")
        _check(lib, lib.axis_init(self._state, ctypes.byref(self.config)))

    def reset(self, angle_rad):
        self._lib.axis_reset(self._state, angle_rad)

    def step(self, ref_rad, angle_rad, rate_rad_s=None):
        """One tick: the torque command (N m). rate_rad_s (gyro) for LP-MLADRC, PID, CASCADED, INDI and RATE-ADRC."""
        lib = self._lib
        torque = lib.real()
        rate = None if rate_rad_s is None else ctypes.byref(lib.real(rate_rad_s))
        lib.axis_step(self._state, ref_rad, angle_rad, rate, ctypes.byref(torque))
        return torque.value

    def set_applied(self, torque_Nm):
        self._lib.axis_set_applied(self._state, torque_Nm)

    @property
    def faults(self):
        return int(self._lib.axis_get_faults(self._state))

    @property
    def consecutive_faults(self):
        return int(self._lib.axis_get_consecutive_faults(self._state))

    def estimate(self):
        """(angle, rate, total disturbance) estimates of the observer."""
        r = self._lib.real
        a, b, c = r(), r(), r()
        self._lib.axis_get_estimate(self._state, ctypes.byref(a), ctypes.byref(b), ctypes.byref(c))
        return a.value, b.value, c.value

    def run(self, ref_rad, angle_rad, rate_rad_s=None, applied_Nm=None):
        """Open loop over arrays of samples: each tick steps, then reports the
        applied torque (applied_Nm[k], or the command itself). Returns the
        commands and the faults per tick as NumPy arrays."""
        lib = self._lib
        ref = np.asarray(ref_rad, dtype=lib.dtype)
        angle = np.asarray(angle_rad, dtype=lib.dtype)
        rate = None if rate_rad_s is None else np.asarray(rate_rad_s, dtype=lib.dtype)
        applied = None if applied_Nm is None else np.asarray(applied_Nm, dtype=lib.dtype)
        u = np.empty(ref.shape, dtype=lib.dtype)
        faults = np.empty(ref.shape, dtype=np.uint8)
        for k in range(ref.shape[0]):
            u[k] = self.step(ref[k], angle[k], None if rate is None else rate[k])
            faults[k] = self.faults
            self.set_applied(u[k] if applied is None else applied[k])
        return u, faults


class Attitude:
    """The three-axis attitude controller (ladrc_attitude_t). config: dict with
    "variant", "dt_s", "inertia_kg_m2" (3 values), "drag_Nms" (for
    ladrc_attitude_config_default), optionally "coupling_feed", "axis" (a dict
    of axis fields for all three axes) and "roll" / "pitch" / "yaw" (per axis)."""

    def __init__(self, config):
        lib = self._lib = library()
        config = dict(config)
        try:
            variant, dt_s, inertia, drag = (config.pop(k) for k in ("variant", "dt_s", "inertia_kg_m2", "drag_Nms"))
        except KeyError as e:
            raise KeyError(f"attitude config needs {e}") from None
        inertia = lib.array(inertia, 3, "inertia_kg_m2")
        cfg = lib.AttitudeConfig()
        lib.attitude_config_default(ctypes.byref(cfg), _enum_value("variant", variant), dt_s,
                                    _real_ptr(lib, inertia), drag)
        every = config.pop("axis", {})
        per_axis = [config.pop(n, {}) for n in ("roll", "pitch", "yaw")]
        if "coupling_feed" in config:
            cfg.coupling_feed = int(config.pop("coupling_feed"))
        if config:
            raise KeyError(f"attitude config: unknown keys {sorted(config)}")
        for i in range(3):
            _apply(cfg.axis[i], {**every, **per_axis[i]}, ("roll", "pitch", "yaw")[i] + " config")
        self.config = cfg
        self._state = lib.state("attitude_t")
        failed = ctypes.c_int(-1)
        _check(lib, lib.attitude_init(self._state, ctypes.byref(cfg), ctypes.byref(failed)), failed.value)
        self._torque = np.zeros(3, dtype=lib.dtype)

    def reset(self, angle_rad):
        a = self._lib.array(angle_rad, 3, "angle_rad")
        self._lib.attitude_reset(self._state, _real_ptr(self._lib, a))

    def step(self, ref_rad, angle_rad, rate_rad_s=None):
        """One tick: (torques roll, pitch, yaw as a NumPy array, fault flags)."""
        lib = self._lib
        ref = lib.array(ref_rad, 3, "ref_rad")
        angle = lib.array(angle_rad, 3, "angle_rad")
        rate = None if rate_rad_s is None else lib.array(rate_rad_s, 3, "rate_rad_s")
        torque = np.empty(3, dtype=lib.dtype)
        faults = lib.attitude_step(self._state, _real_ptr(lib, ref), _real_ptr(lib, angle),
                                   None if rate is None else _real_ptr(lib, rate), _real_ptr(lib, torque))
        return torque, int(faults)

    def set_applied(self, torque_Nm):
        t = self._lib.array(torque_Nm, 3, "torque_Nm")
        self._lib.attitude_set_applied(self._state, _real_ptr(self._lib, t))


class MixerOutput:
    """What a mixer step gives: NumPy arrays w2_rad2_s2 (4), w_rad_s (4),
    torque_Nm (3, achieved), thrust_N, the saturated bits and fault flags."""

    def __init__(self, c, dtype):
        self.w2_rad2_s2 = np.array(c.w2_rad2_s2[:], dtype=dtype)
        self.w_rad_s = np.array(c.w_rad_s[:], dtype=dtype)
        self.thrust_N = dtype(c.thrust_N)
        self.torque_Nm = np.array(c.torque_Nm[:], dtype=dtype)
        self.saturated = int(c.saturated)
        self.faults = int(c.faults)


class Mixer:
    """The plus-frame mixer (ladrc_mixer_t). config: dict of every field of
    ladrc_mixer_config_t; "mode" defaults to "SATURATE"."""

    def __init__(self, config):
        lib = self._lib = library()
        cfg = lib.MixerConfig()
        config = {"mode": "SATURATE", **config}
        missing = [f[0] for f in cfg._fields_ if f[0] not in config]
        if missing:
            raise KeyError(f"mixer config needs {missing}")
        _apply(cfg, config, "mixer config")
        self.config = cfg
        self._state = lib.state("mixer_t")
        _check(lib, lib.mixer_init(self._state, ctypes.byref(cfg)))
        self._out = lib.MixerOutputC()

    def reset(self):
        self._lib.mixer_reset(self._state)

    def thrust_from_tilt(self, roll_rad, pitch_rad):
        return self._lib.mixer_thrust_from_tilt(self._state, roll_rad, pitch_rad)

    def step(self, thrust_N, torque_Nm):
        lib = self._lib
        t = lib.array(torque_Nm, 3, "torque_Nm")
        lib.mixer_step(self._state, thrust_N, _real_ptr(lib, t), ctypes.byref(self._out))
        return MixerOutput(self._out, lib.dtype)
