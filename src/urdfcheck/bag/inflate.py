"""Decompression with an output bound: a chunk never inflates past what it declares, nor a recording past a total.

A 1 KB zstd chunk can declare 1 KB and inflate to 2.5 GB (issue 36). Each codec is asked for at most the
declared size plus one byte, in memory (never a temporary file): one byte more than declared is a refusal.
"""
from __future__ import annotations

MAX_CHUNK = 256 * 1024**2  # one chunk or one message, inflated
MAX_MESSAGE = 16 * 1024**2  # one message compressed alone (rosbag2 "message" mode), which declares no size
MAX_TOTAL = 16 * 1024**3  # one recording, inflated in all (the run's time budget usually stops it first)


class InflateError(ValueError):
    pass


class Inflater:
    """Counts what one recording inflates."""

    def __init__(self, total: int = MAX_TOTAL, chunk: int = MAX_CHUNK, message: int = MAX_MESSAGE):
        self.total, self.chunk, self.message, self.used = total, chunk, message, 0

    def inflate(self, codec: str, data: bytes, declared: int | None, what: str = "a chunk") -> bytes:
        codec = (codec or "").lower()
        if codec in ("", "none"):
            return data
        cap = self.message if declared is None else declared
        if cap > self.chunk:
            raise InflateError(f"{what} declares {cap} bytes inflated, more than the {self.chunk >> 20} MiB "
                               "allowed for one")
        if self.used + cap > self.total:
            raise InflateError(f"the recording inflates past {self.total >> 30} GiB in all")
        out = _decompress(codec, data, cap + 1)
        if len(out) > cap:
            if declared is None:
                raise InflateError(f"{what} inflates past {cap >> 20} MiB (a decompression bomb?)")
            raise InflateError(f"{what} inflates past its declared size of {cap} bytes (a decompression bomb)")
        self.used += len(out)
        return out


def _decompress(codec: str, data: bytes, max_length: int) -> bytes:
    try:
        if codec == "zstd":
            try:
                from compression import zstd  # Python 3.14
            except ImportError:
                from backports import zstd  # what rosbags depends on before 3.14
            return zstd.ZstdDecompressor().decompress(data, max_length=max_length)
        if codec == "lz4":
            import lz4.frame

            return lz4.frame.LZ4FrameDecompressor().decompress(data, max_length=max_length)
        if codec == "bz2":
            import bz2

            return bz2.BZ2Decompressor().decompress(data, max_length=max_length)
    except ImportError:
        raise InflateError(f"cannot decompress {codec}: its module is not installed") from None
    except (OSError, ValueError, EOFError, RuntimeError) as e:
        raise InflateError(f"a {codec} block cannot be decompressed: {e}") from None
    except Exception as e:  # noqa: BLE001 - zstd and lz4 raise their own error types for corrupt data
        raise InflateError(f"a {codec} block cannot be decompressed: {type(e).__name__}: {e}") from None
    raise InflateError(f"unknown compression {codec!r}")
