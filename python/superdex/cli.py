"""The `superdex` command.

    superdex view RECORDING [--port N] [--no-browser]

serves the scene debugger's page in replay mode for a recording (docs/recording_format.md): the
page shows every frame of the run with a timeline, with no simulation running. It opens the
page in a browser where one can be opened and prints the URL otherwise (over SSH, forward the
port: `ssh -L N:127.0.0.1:N host`). Ctrl-C (SIGINT) or SIGTERM stops it, also when it was started
as a background job of a script (which starts with SIGINT ignored).
"""

import argparse
import os
import signal
import sys
import time
import webbrowser


def _stop_on_signals() -> list:
    """Returns a one-element list whose flag SIGINT and SIGTERM set, whatever disposition the
    process inherited (a shell starts background jobs with SIGINT ignored, and Python then keeps
    it ignored). The
    handlers only set the flag (no lock: a handler runs on the main thread between any two
    bytecodes), so a signal that arrives anywhere, even before the serving loop is entered, stops
    the server cleanly instead of raising KeyboardInterrupt at that point."""
    stop = [False]

    def handler(signum, frame):
        stop[0] = True

    for sig in (signal.SIGINT, signal.SIGTERM):
        signal.signal(sig, handler)
    return stop


def _view(args) -> int:
    from superdex._native import module as _m
    from superdex.physics import debugger

    server = _m.get_debug_server()
    server.set_ui_directory(str(debugger._ui_directory()))
    try:
        server.start_replay(args.recording, args.port)
    except _m.Error as e:
        print(f"superdex view: {e}", file=sys.stderr)
        return 2
    url = server.get_url()
    opened = False
    if not args.no_browser and debugger._can_open_browser():
        try:
            opened = webbrowser.open(url)
        except webbrowser.Error:
            opened = False
    port = server.get_port()
    stop = _stop_on_signals()  # before the URL is printed: whoever reads it may stop the server at once
    try:
        print(f"superdex view: replaying {args.recording} at {url}" + ("" if opened else f" (over SSH: ssh -L {port}:127.0.0.1:{port} <this host>)"),
              flush=True)
        # Sleep in short naps: a signal's handler runs when it interrupts one
        while not stop[0]:
            time.sleep(0.2)
    finally:
        server.stop()
    return 0


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="superdex", description="SuperDex command-line tools")
    commands = parser.add_subparsers(dest="command", required=True)
    view = commands.add_parser("view", help="replay a recording in the scene debugger's page")
    view.add_argument("recording", help="a recording file (JSON lines, docs/recording_format.md)")
    view.add_argument("--port", type=int, default=int(os.environ.get("SUPERDEX_DEBUGGER_PORT", "0")),
                      help="port on 127.0.0.1 (default: a free one)")
    view.add_argument("--no-browser", action="store_true", help="only print the URL")
    args = parser.parse_args(argv)
    if args.command == "view":
        return _view(args)
    return 2


if __name__ == "__main__":
    sys.exit(main())
