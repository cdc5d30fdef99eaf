"""Where the batch kernels run: the CPU (numba, as ever) or an NVIDIA GPU (numba's CUDA target).

The per-arch kernels (the four-hinge search, the four-link preparation, the response) are
written once, as plain Python under :func:`archrock._jit.maybe_njit`.  :func:`device_function`
compiles the *same source* for the GPU: it rebuilds the function with every compiled function
it calls (by global name or closure) replaced by that callee's own device build, recursively,
and hands it to ``numba.cuda.jit(device=True)``.  Only a callee that allocates (``np.empty``
cannot run inside a GPU thread) has a device replacement of its own, registered with
:func:`device_override` beside it; nothing else is written twice.

Nothing here imports ``numba.cuda`` until a GPU is asked for, so the package imports and runs
with numpy and scipy alone.  ``NUMBA_ENABLE_CUDASIM=1`` runs the device kernels in numba's CUDA
simulator (pure Python, one thread at a time): the tests use it to check the device build
against the CPU's without a GPU.  ``device="auto"`` never picks the simulator.
"""

from __future__ import annotations

import os
import types

from ._jit import HAVE_NUMBA
from .errors import ArchInputError

__all__ = ["DEVICES", "AUTO_MIN_ARCHES", "check_device", "resolve_device", "gpu_present",
           "simulator", "cuda_module", "device_function", "device_kernel", "device_override",
           "builder", "gpu_note"]

#: allowed values of every ``device`` option
DEVICES = ("cpu", "gpu", "auto")
#: ``device="auto"`` takes the GPU from this many arches in a call: below it the launch, the
#: compilation (once per process) and the transfers cost more than the CPU's threads take
AUTO_MIN_ARCHES = 20_000

_OVERRIDES: dict = {}
_BUILT: dict = {}


def check_device(device) -> str:
    """``device`` if it is one of :data:`DEVICES`, else an :class:`ArchInputError` naming them."""
    if not isinstance(device, str) or device.strip().lower() not in DEVICES:
        raise ArchInputError(f"device: {device!r}; allowed {', '.join(DEVICES)}")
    return device.strip().lower()


def simulator() -> bool:
    """Whether numba's CUDA simulator is switched on (``NUMBA_ENABLE_CUDASIM=1``)."""
    return os.environ.get("NUMBA_ENABLE_CUDASIM", "0") not in ("", "0")


def cuda_module():
    """``numba.cuda``, or an :class:`ArchInputError` saying what is missing."""
    if not HAVE_NUMBA:
        raise ArchInputError("device: 'gpu' needs numba (pip install 'archrock[gpu]'); numba is "
                             "absent or switched off (ARCHROCK_NO_NUMBA)")
    try:
        from numba import cuda
    except ImportError as exc:  # pragma: no cover - a numba without its CUDA target
        raise ArchInputError(f"device: 'gpu' needs numba's CUDA target (pip install "
                             f"'archrock[gpu]'): {exc}") from None
    return cuda


def gpu_present() -> bool:
    """Whether a real CUDA GPU can be used (the simulator does not count)."""
    if not HAVE_NUMBA or simulator():
        return False
    try:
        from numba import cuda

        return bool(cuda.is_available())
    except Exception:  # noqa: BLE001 - a broken driver or toolkit means no GPU here
        return False


def gpu_note() -> str:
    """One line on the GPU this process would use, for logs and benchmark headers."""
    if simulator() and HAVE_NUMBA:
        return "numba CUDA simulator (NUMBA_ENABLE_CUDASIM=1): pure Python, for tests only"
    if not gpu_present():
        return "no CUDA GPU"
    cuda = cuda_module()
    dev = cuda.get_current_device()
    name = dev.name.decode() if isinstance(dev.name, bytes) else str(dev.name)
    free, total = cuda.current_context().get_memory_info()
    return (f"{name} (compute capability {dev.compute_capability[0]}."
            f"{dev.compute_capability[1]}, {total / 2**30:.0f} GiB, {free / 2**30:.0f} free)")


def resolve_device(device, n_arches: int = 0) -> str:
    """'cpu' or 'gpu' for a call on ``n_arches`` arches.

    'cpu' is always possible.  'gpu' needs numba's CUDA target and a GPU (or the simulator):
    otherwise an :class:`ArchInputError` says what is missing.  'auto' is the GPU where a real
    one is present and the call has at least :data:`AUTO_MIN_ARCHES` arches, else the CPU.
    """
    device = check_device(device)
    if device == "cpu":
        return "cpu"
    if device == "auto":
        return "gpu" if n_arches >= AUTO_MIN_ARCHES and gpu_present() else "cpu"
    cuda = cuda_module()
    if not simulator() and not gpu_present():
        raise ArchInputError(
            f"device: 'gpu' but no CUDA GPU is usable here ({_why_no_gpu(cuda)}); allowed "
            f"'cpu' or 'auto' (the GPU where one is present), or NUMBA_ENABLE_CUDASIM=1 for "
            f"numba's simulator")
    return "gpu"


def _why_no_gpu(cuda) -> str:
    try:
        cuda.detect()
        return "numba found no device"
    except Exception as exc:  # noqa: BLE001 - the driver's own words, first sentence
        words = " ".join(str(exc).split()).split(". ")[0].strip(" :.")
        return words[:160] or type(exc).__name__


# ------------------------------------------------------------------------- one source, two builds
def _python(func):
    """The Python function behind a numba dispatcher (or the function itself)."""
    return getattr(func, "py_func", func)


def _is_kernel_function(value) -> bool:
    """A numba dispatcher, a registered device replacement, or (numba switched off) a plain
    function of the package: the callees that get a device build."""
    if hasattr(value, "py_func") or any(value is f for f in _OVERRIDES.values()):
        return True
    return (isinstance(value, types.FunctionType)
            and getattr(value, "__module__", "").startswith("archrock."))


def _names(code) -> set:
    """Global names read by ``code`` and the code objects nested in it."""
    out = set(code.co_names)
    for const in code.co_consts:
        if isinstance(const, types.CodeType):
            out |= _names(const)
    return out


def device_override(cpu_function, simulator_only: bool = False):
    """Register the decorated Python function as the device build of ``cpu_function`` (same
    arguments, same results; for a function that allocates, which a GPU thread cannot).
    ``simulator_only``: used under numba's simulator alone, where a device array is read and
    written element by element through Python (a whole-array assignment there costs one call
    where a loop costs thousands)."""
    def register(device_impl):
        if not simulator_only or simulator():
            _OVERRIDES[_python(cpu_function)] = device_impl
            _BUILT.pop(_python(cpu_function), None)
        return device_impl
    return register


def _rebuild(fn, build=None):
    """``fn`` with its compiled callees (globals and closure cells) swapped for their builds by
    ``build`` (default: the CUDA device build)."""
    build = device_function if build is None else build
    glb = dict(fn.__globals__)
    for name in _names(fn.__code__):
        value = glb.get(name)
        if value is not None and _is_kernel_function(value):
            glb[name] = build(value)
    closure = None
    if fn.__closure__:
        closure = tuple(
            types.CellType(build(c.cell_contents))
            if _is_kernel_function(c.cell_contents) else c for c in fn.__closure__)
    new = types.FunctionType(fn.__code__, glb, fn.__name__, fn.__defaults__, closure)
    new.__qualname__ = fn.__qualname__
    new.__doc__ = fn.__doc__
    new.__module__ = fn.__module__
    return new


def builder(jit, built: dict | None = None):
    """A function that builds any kernel function with ``jit`` from its own source, its callees
    built the same way (device replacements included), each once in ``built``.  The CUDA
    device build is ``builder(numba.cuda.jit(device=True))``; ``builder(numba.njit(
    fastmath={"contract"}))`` gives a CPU build that rounds as a GPU does (fused multiply-adds),
    which benchmarks/gpu_rounding.py compares with the plain CPU build."""
    built = {} if built is None else built

    def build(func):
        key = _python(func)
        if key not in built:
            built[key] = None  # a recursive reference gets the placeholder, never a loop
            built[key] = jit(_rebuild(_OVERRIDES.get(key, key), build))
        return built[key]
    return build


def device_function(func):
    """The CUDA device build of ``func`` (a :func:`maybe_njit` function), compiled from the same
    Python source on first use; built once per process."""
    key = _python(func)
    if key not in _BUILT:
        _BUILT[key] = builder(cuda_module().jit(device=True), _BUILT)(func)
    return _BUILT[key]


def device_kernel(func, **callees):
    """A CUDA kernel (``numba.cuda.jit``) from the Python function ``func``, its compiled callees
    swapped for their device builds; ``callees`` name functions its source reads that its
    module does not import at load time (the CPU kernels exist only where numba does).  Built
    once per process."""
    key = ("kernel", func)
    if key not in _BUILT:
        cuda = cuda_module()
        fn = _rebuild(func)
        fn.__globals__["cuda"] = cuda  # the kernel's own module never imports numba.cuda
        for name, value in callees.items():
            fn.__globals__[name] = device_function(value)
        _BUILT[key] = cuda.jit(fn)
    return _BUILT[key]
