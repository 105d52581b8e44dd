"""The scene debugger's entry points (API.md: `debugger.attach`, `debugger.is_attached`).

`attach()` starts the engine's debug server (`get_debug_server()`, 127.0.0.1 only), opens the page
in the user's browser, or prints its URL where no browser can be opened (SSH: forward the port with
`ssh -L PORT:127.0.0.1:PORT host` and open the URL locally), and waits for the page to connect.
`is_attached()` is True while a page is connected; closing the page ends a loop written as
`while debugger.is_attached()`.

Environment variables:

- SUPERDEX_DEBUGGER_RECORD=<file>: no page; `attach()` records every scene's steps to <file>
  (JSON lines, docs/recording_format.md; replay it with `superdex view <file>`) and returns True;
- SUPERDEX_DEBUGGER_DURATION=<seconds>: with or without RECORD, records (default file
  superdex_recording.jsonl) and `is_attached()` stays True until the recorded scenes have been
  simulated that long (a script that only shows scenes through `Scene.update_debugger`, such as
  an IK loop, simulates nothing: its run ends that long on the wall clock after its first frame).
  This is how headless runs (CI, a cluster) use scripts written for the page;
- SUPERDEX_DEBUGGER_FRAME_INTERVAL=<seconds>: simulated time between recorded frames (default
  1/60; 0 records every step);
- SUPERDEX_DEBUGGER_PORT=<port>: the server's port (default: a free one);
- SUPERDEX_DEBUGGER_WAIT=<seconds>: wait at least this long for the page (time to set up an SSH
  tunnel, or a slow browser start);
- SUPERDEX_DEBUGGER_BROWSER=0: never open a browser, only print the URL.
"""

import os
import sys
import time
import webbrowser
from pathlib import Path

from superdex._native import module as _m

_duration = None
_mode = None  # None, "record" or "live"
_frames_since = None  # wall clock (s) at the first frame of a recording that simulates nothing


def _ui_directory() -> Path:
    """The built page: $SUPERDEX_DEBUGGER_UI if set, else the repository's superdex_debugger/dist."""
    override = os.environ.get("SUPERDEX_DEBUGGER_UI")
    return Path(override) if override else Path(__file__).resolve().parents[3] / "superdex_debugger" / "dist"


def _can_open_browser() -> bool:
    if os.environ.get("SUPERDEX_DEBUGGER_BROWSER", "1").strip() in ("0", "false", "no"):
        return False
    # a Linux machine without a display (SSH, containers) has no browser to open
    if sys.platform.startswith("linux") and not (os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")):
        return False
    return True


def _env_seconds(name: str, default=None, allow_zero=False):
    text = os.environ.get(name)
    if text is None or text.strip() == "":
        return default
    try:
        value = float(text)
    except ValueError:
        raise _m.Error(f"{name}: expected a number of seconds, got {text!r}") from None
    if not (value > 0 or (allow_zero and value == 0)):
        raise _m.Error(f"{name}: must be {'>= 0' if allow_zero else 'positive'}, got {text!r}")
    return value


def _attach_recording() -> bool:
    global _duration, _mode, _frames_since
    _frames_since = None
    _duration = _env_seconds("SUPERDEX_DEBUGGER_DURATION")
    frame_interval = _env_seconds("SUPERDEX_DEBUGGER_FRAME_INTERVAL", 1.0 / 60, allow_zero=True)
    path = os.environ.get("SUPERDEX_DEBUGGER_RECORD") or "superdex_recording.jsonl"
    _m.start_recording(path, frame_interval)
    _mode = "record"
    span = f"{_duration:g} simulated seconds" if _duration is not None else "until detach()"
    print(f"superdex.debugger: no display; recording to {path} for {span}", flush=True)
    return True


def _attach_live(timeout_seconds: float) -> bool:
    global _mode
    server = _m.get_debug_server()
    if not server.has_started():
        port_text = os.environ.get("SUPERDEX_DEBUGGER_PORT", "0")
        try:
            port = int(port_text)
        except ValueError:
            raise _m.Error(f"SUPERDEX_DEBUGGER_PORT: expected a port number, got {port_text!r}") from None
        server.set_ui_directory(str(_ui_directory()))
        server.start(port)
    url = server.get_url()
    opened = False
    if _can_open_browser():
        try:
            opened = webbrowser.open(url)
        except webbrowser.Error:
            opened = False
    if not opened:
        port = server.get_port()
        print(f"superdex.debugger: open {url} in a browser (over SSH: ssh -L {port}:127.0.0.1:{port} <this host>)", flush=True)
    timeout_seconds = max(timeout_seconds, _env_seconds("SUPERDEX_DEBUGGER_WAIT", 0.0, allow_zero=True))
    if not server.wait_for_connection(timeout_seconds):
        print(f"superdex.debugger: no page connected within {timeout_seconds:g} s", file=sys.stderr, flush=True)
        server.stop()
        return False
    _mode = "live"
    return True


def attach(timeout_seconds: float = 5.0) -> bool:
    """Starts the debug server, opens the page (or prints its URL) and waits up to
    `timeout_seconds` for it to connect; True when a page is connected. With
    SUPERDEX_DEBUGGER_RECORD or SUPERDEX_DEBUGGER_DURATION set, records to a file instead."""
    if not (timeout_seconds >= 0):
        raise _m.Error(f"attach: timeout_seconds must be >= 0, got {timeout_seconds!r}")
    if is_attached():
        return True
    if os.environ.get("SUPERDEX_DEBUGGER_RECORD") or os.environ.get("SUPERDEX_DEBUGGER_DURATION"):
        return _attach_recording()
    return _attach_live(timeout_seconds)


def is_attached() -> bool:
    """True while a page is connected, or while a headless recording runs (one with a duration
    ends, and closes its file, once the recorded scenes have been simulated that long)."""
    global _mode, _frames_since
    if _mode == "live":
        if _m.get_debug_server().has_connection():
            return True
        detach()
        return False
    if _mode == "record":
        if not _m.is_recording():
            _mode = None
            return False
        # (float builds step by float dt: allow its rounding)
        if _duration is not None and _m.recorded_time() >= _duration * (1 - 1e-6):
            detach()
            return False
        # a script that shows scenes without stepping them (Scene.update_debugger, an IK loop)
        # simulates nothing: its duration runs on the wall clock from its first frame
        if _duration is not None and _m.recorded_time() == 0 and _m.recorded_frames() > 0:
            if _frames_since is None:
                _frames_since = time.monotonic()
            elif time.monotonic() - _frames_since >= _duration:
                detach()
                return False
        return True
    return False


def detach() -> None:
    """Ends the recording, or closes the page's connection and stops the server."""
    global _mode
    if _mode == "record" and _m.is_recording():
        print(f"superdex.debugger: recorded {_m.recorded_time():g} s of simulation", flush=True)
        _m.stop_recording()
    elif _mode == "live":
        _m.get_debug_server().stop()
    _mode = None
