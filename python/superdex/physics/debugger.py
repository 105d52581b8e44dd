"""The scene debugger's entry points (API.md: `debugger.attach`, `debugger.is_attached`).

Headless runs (CI, a cluster, SSH without a forwarded port) record instead of serving the page:

- SUPERDEX_DEBUGGER_RECORD=<file>: `attach()` starts recording every scene's steps to <file>
  (JSON lines, docs/recording_format.md) and returns True;
- SUPERDEX_DEBUGGER_DURATION=<seconds>: `is_attached()` stays True until the recorded scenes have
  been simulated that long, then the recording is closed (default file superdex_recording.jsonl);
- SUPERDEX_DEBUGGER_FRAME_INTERVAL=<seconds>: simulated time between recorded frames (default
  1/60; 0 records every step).

The interactive web page is not part of this build yet: without these variables `attach()` says
so and returns False, and a script written as `if debugger.attach(): loop` ends cleanly.
"""

import os
import sys

from superdex._native import module as _m

_duration = None
_attached = False


def attach(timeout_seconds: float = 5.0) -> bool:
    """Attaches the debugger: records to a file when SUPERDEX_DEBUGGER_RECORD or
    SUPERDEX_DEBUGGER_DURATION is set. Returns whether something is attached."""
    global _duration, _attached
    if _attached and _m.is_recording():
        return True
    path = os.environ.get("SUPERDEX_DEBUGGER_RECORD")
    duration = os.environ.get("SUPERDEX_DEBUGGER_DURATION")
    if not path and not duration:
        print("superdex.debugger: the interactive web debugger is not available in this build; set "
              "SUPERDEX_DEBUGGER_RECORD=<file> and SUPERDEX_DEBUGGER_DURATION=<seconds> to record the run instead",
              file=sys.stderr)
        return False
    try:
        _duration = float(duration) if duration else None
    except ValueError:
        raise _m.Error(f"SUPERDEX_DEBUGGER_DURATION: expected a number of seconds, got {duration!r}") from None
    if _duration is not None and not _duration > 0:
        raise _m.Error(f"SUPERDEX_DEBUGGER_DURATION: must be positive, got {duration!r}")
    interval = os.environ.get("SUPERDEX_DEBUGGER_FRAME_INTERVAL", str(1.0 / 60))
    try:
        frame_interval = float(interval)
    except ValueError:
        raise _m.Error(f"SUPERDEX_DEBUGGER_FRAME_INTERVAL: expected a number of seconds, got {interval!r}") from None
    path = path or "superdex_recording.jsonl"
    _m.start_recording(path, frame_interval)
    _attached = True
    span = f"{_duration:g} simulated seconds" if _duration is not None else "until detach()"
    print(f"superdex.debugger: no display; recording to {path} for {span}", flush=True)
    return True


def is_attached() -> bool:
    """True while attached; a headless recording with a duration ends (and closes its file) once
    the recorded scenes have been simulated that long."""
    global _attached
    if not _attached:
        return False
    if not _m.is_recording():
        _attached = False
        return False
    # (float builds step by float dt: allow its rounding)
    if _duration is not None and _m.recorded_time() >= _duration * (1 - 1e-6):
        detach()
        return False
    return True


def detach() -> None:
    """Closes the recording (and, later, the page's connection)."""
    global _attached
    if _attached and _m.is_recording():
        print(f"superdex.debugger: recorded {_m.recorded_time():g} s of simulation", flush=True)
    _attached = False
    _m.stop_recording()
