# On the cuda backend field() hands each field over through DLPack: CuPy and PyTorch read it in place on
# the device, the same bytes as the cpu backend's field. Needs a CUDA device and CuPy or PyTorch (the GPU
# machine: scripts/gpu-check python); skipped, saying why, anywhere else.
import ctypes
import gc
import importlib

import numpy as np
import pytest

import bleedsim
from conftest import DEFAULT

FRAMES = 5


def library(name):
    try:
        return importlib.import_module(name)
    except ImportError:
        pytest.skip(f"{name} is not installed here")


def pair():
    """The default scene on the cpu and on the cuda backend."""
    scenario = bleedsim.load_scenario(str(DEFAULT))
    try:
        cuda = bleedsim.Simulation(scenario, backend="cuda")
    except RuntimeError as no_cuda:
        pytest.skip(f"no cuda backend here: {no_cuda}")
    return bleedsim.Simulation(scenario, backend="cpu"), cuda


def on_host(name, tensor):
    """A consumer's tensor as NumPy, and where it lies on the device."""
    if name == "cupy":
        return tensor.get(), tensor.data.ptr
    assert tensor.is_cuda
    return tensor.cpu().numpy(), tensor.data_ptr()


@pytest.mark.parametrize("consumer", ["cupy", "torch"])
def test_every_field_read_in_place_is_the_cpu_runs(consumer):
    module = library(consumer)
    cpu, cuda = pair()
    cpu.step(FRAMES)
    cuda.step(FRAMES)
    for name in cpu.field_names():
        field = cuda.field(name)
        assert isinstance(field, bleedsim.DeviceField)
        assert field.__dlpack_device__() == (2, 0)
        host, _ = on_host(consumer, module.from_dlpack(field))
        expected = cpu.field(name)
        assert (host.shape, host.dtype) == (expected.shape, expected.dtype) == (field.shape, field.dtype), name
        assert host.tobytes() == expected.tobytes(), name


@pytest.mark.parametrize("consumer", ["cupy", "torch"])
def test_a_tensor_shows_the_next_frame_in_place_and_keeps_the_simulation_alive(consumer):
    module = library(consumer)
    cpu, cuda = pair()
    cpu.step()
    cuda.step()
    first = module.from_dlpack(cuda.field("frame"))
    cpu.step()
    cuda.step()
    again = module.from_dlpack(cuda.field("frame"))  # waits for the frame: `first` may be read now
    (now, at), (_, at_again) = on_host(consumer, first), on_host(consumer, again)
    assert at == at_again
    assert now.tobytes() == cpu.field("frame").tobytes()  # the second frame, in the first tensor
    del cuda, again
    gc.collect()
    assert on_host(consumer, first)[0].tobytes() == cpu.field("frame").tobytes()


def capsule_name(capsule):
    get_name = ctypes.pythonapi.PyCapsule_GetName
    get_name.restype, get_name.argtypes = ctypes.c_char_p, [ctypes.py_object]
    return get_name(capsule).decode()


def test_the_capsules_say_what_they_are():
    _, cuda = pair()
    cuda.step()
    field = cuda.field("spread/stain")
    assert capsule_name(field.__dlpack__()) == "dltensor"  # a consumer that asks for no version
    versioned = field.__dlpack__(max_version=(1, 0), stream=-1)
    assert capsule_name(versioned) == "dltensor_versioned"
    get_pointer = ctypes.pythonapi.PyCapsule_GetPointer
    get_pointer.restype, get_pointer.argtypes = ctypes.c_void_p, [ctypes.py_object, ctypes.c_char_p]
    # DLManagedTensorVersioned: version (2 × uint32), manager_ctx, deleter, flags (uint64), ...
    major, minor, _, _, flags = np.frombuffer(
        ctypes.string_at(get_pointer(versioned, b"dltensor_versioned"), 32), dtype="<u4, <u4, <u8, <u8, <u8")[0]
    assert (major, minor, flags & 1) == (1, 0, 1)  # DLPack 1.0, read-only
    with pytest.raises(BufferError, match="in place only"):
        field.__dlpack__(copy=True)
    with pytest.raises(BufferError, match="CUDA device 0"):
        field.__dlpack__(dl_device=(1, 0))
