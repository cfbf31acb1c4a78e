"""Start the ParaView GUI under xvfb-run with the plugin on PV_PLUGIN_PATH and a --script.

    pvpython run_gui.py --xvfb-run xvfb-run --paraview paraview --plugin-dir DIR
                        --script gui_apply_filter.py --marker marker.txt [--timeout 90]

Runs `paraview --dr --script=SCRIPT --exit` (--dr: no user settings; --exit: quit after the
script) with PV_PLUGIN_PATH=DIR and PSS_GUI_MARKER=marker. Passes when paraview exits with 0 and
the script wrote a marker that starts with "OK" during this run.
"""
import argparse
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pss_xvfb  # noqa: E402

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--xvfb-run", required=True)
parser.add_argument("--paraview", required=True)
parser.add_argument("--plugin-dir", required=True)
parser.add_argument("--script", required=True)
parser.add_argument("--marker", required=True)
parser.add_argument("--timeout", type=int, default=90)
args = parser.parse_args()

if os.path.exists(args.marker):
    os.remove(args.marker)
env = dict(os.environ)
env["PV_PLUGIN_PATH"] = os.path.abspath(args.plugin_dir)
env["PSS_GUI_MARKER"] = os.path.abspath(args.marker)
env.pop("PARAVIEW_DATA_ROOT", None)
started = time.time()
status, output = pss_xvfb.run(args.xvfb_run, [args.paraview, "--dr", "--script=%s" % os.path.abspath(args.script), "--exit"],
                              env=env, timeout=args.timeout)
print(output.strip())
print("paraview exit status %d after %.1f s" % (status, time.time() - started))
marker = open(args.marker).read().strip() if os.path.exists(args.marker) else ""
print("marker: %s" % (marker or "(none)"))
ok = status == 0 and marker.startswith("OK") and os.path.getmtime(args.marker) >= started - 1
print("PASS" if ok else "FAIL")
sys.exit(0 if ok else 1)
