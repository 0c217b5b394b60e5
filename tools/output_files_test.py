#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Tests of tools/output_files.py and of every Python tool that takes an output path:

- the module: a file written whole (no temporary left, the earlier file untouched when the write
  fails, a figure in the format its extension names, the permissions), the clash of an output with
  an input (the same path, a symbolic link, a hard link, two outputs the same), the removal of a
  tool's earlier outputs;
- each tool run with an output pointed at one of its inputs (the same path, or a link to it): exit
  status 2, a message naming the file, and the folder byte for byte as it was (the input unchanged,
  nothing created, no temporary left);
- the tools still write where nothing clashes (log_excerpt.py, margins_plot.py), and figures.py
  and campaign.py merge remove their own earlier outputs that this run did not draw again.

Inputs are made here, in the form each tool reads, small (the whole test runs in seconds).
"""

import contextlib
import io
import os
import shutil
import stat
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import output_files as of  # noqa: E402

USAGE = of.USAGE_STATUS


def snapshot(root):
    """{relative path: bytes, or ('link', target), or 'dir'} of everything under root: two snapshots
    equal when no file changed, none was created or removed, and no temporary was left."""
    state = {}
    for d, dirs, files in os.walk(root):
        for name in dirs + files:
            p = os.path.join(d, name)
            rel = os.path.relpath(p, root)
            if os.path.islink(p):
                state[rel] = ("link", os.readlink(p))
            elif os.path.isdir(p):
                state[rel] = "dir"
            else:
                with open(p, "rb") as f:
                    state[rel] = f.read()
    return state


def write(path, data):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb" if isinstance(data, bytes) else "w") as f:
        f.write(data)
    return path


def tool(name, *args):
    """Runs tools/NAME with args; (exit status, stdout, stderr)."""
    p = subprocess.run([sys.executable, os.path.join(HERE, name), *args], stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, text=True, timeout=120)
    return p.returncode, p.stdout, p.stderr


# A time series in ladrc_sil's form (docs/csv-format.md), a few rows: what the figure tools read.
SERIES = ("t_s,angle_roll_deg,error_roll_deg,error_pitch_deg,error_yaw_deg\n"
          "0,0,0,0,0\n0.001,0.1,0.1,0,0\n0.002,0.2,0.1,0,0\n")
METRICS = "scenario,controller,table,quantity,axis,value\npaper,LADRC,4,rms,roll,0.5\n"
# A loop transfer in ladrc_margins --csv's form: the margins on the first line, then the columns.
MARGINS = ("# pm_deg=45 gm_db=10 wc_rad_s=20 gm_rad_s=80\nw_rad_s,L_mag_db,L_phase_deg,L_re,L_im\n"
           "1,40,-95,-8.7,-99.6\n10,10,-120,-1.6,-2.7\n100,-20,-200,-0.09,0.03\n")


class Module(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="output_files_test.")
        self.addCleanup(shutil.rmtree, self.dir)

    def path(self, *parts):
        return os.path.join(self.dir, *parts)

    def test_write_whole_replaces_and_leaves_no_temporary(self):
        p = write(self.path("a.txt"), "earlier\n")
        of.write_whole(p, "new\n")
        of.write_whole(self.path("b.bin"), b"\x00\x01")
        self.assertEqual(snapshot(self.dir), {"a.txt": b"new\n", "b.bin": b"\x00\x01"})

    def test_failed_write_leaves_the_earlier_file_and_no_temporary(self):
        p = write(self.path("a.txt"), "earlier\n")
        before = snapshot(self.dir)
        for error in (RuntimeError("disk full"), SystemExit(1), KeyboardInterrupt()):
            with self.assertRaises(type(error)):
                with of.whole_file(p) as f:
                    f.write("half of the new")
                    raise error
            self.assertEqual(snapshot(self.dir), before, type(error).__name__)

    def test_failed_write_of_a_new_file_leaves_nothing(self):
        with self.assertRaises(ValueError):
            with of.whole_file(self.path("new.txt"), "wb") as f:
                f.write(b"x")
                raise ValueError("bad value")
        self.assertEqual(snapshot(self.dir), {})

    def test_only_whole_writes(self):
        with self.assertRaises(ValueError):
            with of.whole_file(self.path("a.txt"), "a"):
                pass
        self.assertEqual(snapshot(self.dir), {})

    def test_permissions_of_a_new_file_and_of_a_replaced_one(self):
        umask = os.umask(0o022)
        try:
            of.write_whole(self.path("new.txt"), "x")
            p = write(self.path("script.sh"), "#!/bin/sh\n")
            os.chmod(p, 0o750)
            of.write_whole(p, "#!/bin/sh\necho\n")
        finally:
            os.umask(umask)
        # mkstemp makes its file 0600: a new output gets what open() would give, a replaced one keeps its own
        self.assertEqual(stat.S_IMODE(os.stat(self.path("new.txt")).st_mode), 0o644)
        self.assertEqual(stat.S_IMODE(os.stat(p).st_mode), 0o750)

    def test_an_output_link_is_replaced_not_written_through(self):
        target = write(self.path("target.txt"), "kept\n")
        os.symlink("target.txt", self.path("link.txt"))
        of.write_whole(self.path("link.txt"), "new\n")
        self.assertEqual(snapshot(self.dir), {"target.txt": b"kept\n", "link.txt": b"new\n"})
        self.assertTrue(os.path.isfile(target))

    def test_figure_in_the_format_of_its_extension(self):
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots()
        ax.plot([0, 1], [1, 0])
        magic = {"a.png": b"\x89PNG", "a.svg": b"<?xml", "a.pdf": b"%PDF"}
        for name in magic:
            of.save_figure(fig, self.path(name))
        state = snapshot(self.dir)
        self.assertEqual(sorted(state), sorted(magic))
        for name, head in magic.items():
            self.assertTrue(state[name].startswith(head), name)
        # a format matplotlib does not write: refused, the earlier file left as it was, no temporary
        p = write(self.path("a.csv"), "t_s\n0\n")
        before = snapshot(self.dir)
        with self.assertRaises(ValueError):
            of.save_figure(fig, p)
        self.assertEqual(snapshot(self.dir), before)
        plt.close(fig)

    def test_clash_with_an_input(self):
        inp = write(self.path("in.csv"), "a\n")
        os.symlink("in.csv", self.path("sym.csv"))
        os.link(inp, self.path("hard.csv"))
        write(self.path("other.csv"), "a\n")  # the same bytes, another file
        for out in ("in.csv", "sym.csv", "hard.csv", "./in.csv", "sub/../in.csv"):
            found = of.clash({"--out": self.path(out)}, [inp])
            self.assertIsNotNone(found, out)
            self.assertEqual(found[0], "--out")
            self.assertIn(inp, found[2])
        self.assertIsNone(of.clash({"--out": self.path("other.csv")}, [inp]))
        self.assertIsNone(of.clash({"--out": self.path("new.csv")}, [inp]))
        self.assertIsNone(of.clash({"--out": None}, [inp]))  # an output not asked for
        # an input that does not exist (yet) at the output's path is still the output's path
        self.assertIsNotNone(of.clash({"--out": self.path("x.ini")}, [self.path("x.ini")]))

    def test_clash_of_two_outputs(self):
        found = of.clash({"--docs": self.path("a.md"), "--figure": self.path("a.md")}, [])
        self.assertEqual(found[:2], ("--docs", self.path("a.md")))
        self.assertIn("--figure", found[2])
        self.assertIsNone(of.clash([self.path("a.png"), self.path("b.png")], []))

    def test_refusal_exits_2_naming_both(self):
        inp = write(self.path("log.bbl"), b"H x\n")
        err = io.StringIO()
        with contextlib.redirect_stderr(err), self.assertRaises(SystemExit) as e:
            of.refuse_inputs("tool.py", {"OUT": inp}, [inp])
        self.assertEqual(e.exception.code, USAGE)
        self.assertIn("tool.py: OUT %s is the same file as its input %s" % (inp, inp), err.getvalue())

    def test_input_inside_a_replaced_folder(self):
        inp = write(self.path("views", "LOG.csv"), "t_s\n")
        err = io.StringIO()
        with contextlib.redirect_stderr(err), self.assertRaises(SystemExit) as e:
            of.refuse_inside("tool.py", {"views/": self.path("views")}, [inp])
        self.assertEqual(e.exception.code, USAGE)
        self.assertIn("views/ %s holds its input %s" % (self.path("views"), inp), err.getvalue())
        of.refuse_inside("tool.py", {"views/": self.path("views2")}, [inp])  # a folder named alike: not inside

    def test_figure_formats(self):
        err = io.StringIO()
        of.refuse_figure_formats("tool.py", {"--figure": self.path("a.svg"), "--out": None})
        with contextlib.redirect_stderr(err), self.assertRaises(SystemExit) as e:
            of.refuse_figure_formats("tool.py", {"--figure": self.path("a.txt")})
        self.assertEqual(e.exception.code, USAGE)
        self.assertIn("--figure %s: matplotlib writes no .txt figure" % self.path("a.txt"), err.getvalue())

    def test_remove_earlier_only_its_own_names_not_written(self):
        for name in ("map_roll_a.png", "map_pitch_a.png", "rms_roll.png", "notes.png", "map_roll_a.csv"):
            write(self.path(name), "x")
        with contextlib.redirect_stderr(io.StringIO()):
            removed = of.remove_earlier("t", self.dir, ("map_*.png", "rms_*.png"), [self.path("map_roll_a.png")])
        self.assertEqual(sorted(os.path.basename(p) for p in removed), ["map_pitch_a.png", "rms_roll.png"])
        self.assertEqual(sorted(snapshot(self.dir)), ["map_roll_a.csv", "map_roll_a.png", "notes.png"])
        self.assertEqual(of.remove_earlier("t", self.path("nowhere"), ("*",), []), [])


class Tools(unittest.TestCase):
    """Each tool with an output pointed at one of its inputs: refused, nothing changed."""

    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="output_files_test.")
        self.addCleanup(shutil.rmtree, self.dir)

    def path(self, *parts):
        return os.path.join(self.dir, *parts)

    def refused(self, name, args, clashing):
        """Runs tools/NAME args and checks the refusal: exit 2, the clashing file named, the folder
        as it was."""
        before = snapshot(self.dir)
        rc, out, err = tool(name, *args)
        self.assertEqual(rc, USAGE, "%s %s: exit %d\n%s%s" % (name, args, rc, out, err))
        self.assertIn(clashing, err, name)
        self.assertIn("refusing to write over it", err, name)
        self.assertEqual(snapshot(self.dir), before, "%s changed its folder" % name)

    def linked(self, target, *link):
        """A symbolic link at self.path(*link) to target."""
        p = self.path(*link)
        os.makedirs(os.path.dirname(p), exist_ok=True)
        os.symlink(target, p)
        return p

    def synthetic_log(self):
        p = self.path("flight.bbl")
        rc, _, err = tool("bbl_synth.py", p, "0.02")  # 20 kB
        self.assertEqual(rc, 0, err)
        return p

    def test_log_excerpt(self):
        log = self.synthetic_log()
        self.refused("log_excerpt.py", ["cut", log, log], log)
        self.refused("log_excerpt.py", ["cut", log, self.linked(log, "link.bbl")], log)
        # where nothing clashes it writes the excerpt, and nothing beside it
        before = snapshot(self.dir)
        rc, _, err = tool("log_excerpt.py", "cut", log, self.path("cut.bbl"), "--max-bytes", "5000")
        self.assertEqual(rc, 0, err)
        after = snapshot(self.dir)
        self.assertEqual(sorted(after), sorted(list(before) + ["cut.bbl"]))
        self.assertTrue(0 < len(after["cut.bbl"]) <= 5000 + 1000)  # the budget, plus the header kept whole

    def test_margins_plot(self):
        a, b = write(self.path("LADRC.csv"), MARGINS), write(self.path("PID.csv"), MARGINS)
        self.refused("margins_plot.py", [a, b, "-o", b], b)
        rc, _, err = tool("margins_plot.py", a, b, "-o", self.path("margins.png"))
        self.assertEqual(rc, 0, err)
        self.assertEqual(sorted(snapshot(self.dir)), ["LADRC.csv", "PID.csv", "margins.png"])

    def test_figure_format_refused_before_anything_is_written(self):
        a = write(self.path("LADRC.csv"), MARGINS)
        before = snapshot(self.dir)
        rc, _, err = tool("margins_plot.py", a, "-o", self.path("margins.txt"))
        self.assertEqual((rc, snapshot(self.dir)), (USAGE, before), err)
        page = write(self.path("page.md"), "<!-- large-angle:begin -->\n<!-- large-angle:end -->\n")
        os.makedirs(self.path("out"))
        before = snapshot(self.dir)
        rc, _, err = tool("large_angle.py", self.path("out"), "--docs", page, "--figure", self.path("fig.txt"))
        self.assertEqual((rc, snapshot(self.dir)), (USAGE, before), err)  # the page not rewritten either

    def test_closed_loop_views(self):
        d = self.path("replay")
        write(os.path.join(d, "airframe.ini"), "[vehicle]\n")
        ref = write(os.path.join(d, "log_reference.csv"), "t_s\n")
        self.refused("closed_loop_views.py", [d, ref, "--format", "generic", "--bin", self.path("bin")], ref)
        inside = write(os.path.join(d, "closed_loop", "LOG.csv"), "t_s\n")
        before = snapshot(self.dir)
        rc, _, err = tool("closed_loop_views.py", d, inside, "--format", "generic", "--bin", self.path("bin"))
        self.assertEqual((rc, snapshot(self.dir)), (USAGE, before), err)
        self.assertIn("holds its input %s" % inside, err)

    def test_hp_gate_plot(self):
        case = self.path("case")
        hp = write(os.path.join(case, "HP-MLADRC.csv"), SERIES)
        write(os.path.join(case, "signals.csv"), "signal,axis,kind,from_s,to_s\n")
        self.refused("hp_gate_plot.py", [case, "--out", hp], hp)

    def test_hp_gate_docs(self):
        metrics = write(self.path("gate", "case", "metrics.csv"), METRICS)
        self.refused("hp_gate.py", ["--no-run", "--out", self.path("gate"), "--docs", metrics], metrics)

    def test_report(self):
        out = self.path("out")
        metrics = write(os.path.join(out, "paper", "metrics.csv"), METRICS)
        tables = write(os.path.join(out, "tables.txt"), "tables\n")
        self.refused("report.py", [out, metrics], metrics)
        self.refused("report.py", [out, tables], tables)
        page = write(self.path("README.md"), "<!-- headline:begin -->\n<!-- headline:end -->\n")
        self.refused("report.py", [out, page, "--front-page", page], page)

    def test_large_angle_and_vibration(self):
        out = self.path("out")
        series = write(os.path.join(out, "tuned", "flips", "LADRC.csv"), SERIES)
        for name in ("large_angle.py", "vibration.py"):
            self.refused(name, [out, "--figure", series], series)
            self.refused(name, [out, "--docs", series], series)
            page = write(self.path("page.md"), "text\n")
            self.refused(name, [out, "--docs", page, "--figure", page], page)

    def test_figures(self):
        out, figs = self.path("out"), self.path("figs")
        series = write(os.path.join(out, "paper", "HP-MLADRC.csv"), SERIES)
        self.linked(series, "figs", "fig06_tracking.png")
        self.refused("figures.py", [out, figs], series)

    def test_figures_removes_its_figures_not_drawn(self):
        figs = self.path("figs")
        write(os.path.join(figs, "fig06_tracking.png"), b"an earlier run's")
        write(os.path.join(figs, "fig14_estimators_paper.png"), b"estimators_plot.py's")
        write(os.path.join(figs, "photo.png"), b"not a figure of this tool")
        os.makedirs(self.path("out"))
        rc, _, err = tool("figures.py", self.path("out"), figs)
        self.assertEqual(rc, 1, err)  # every scenario missing: an error, and no figure of it left
        self.assertIn("removed %s" % os.path.join(figs, "fig06_tracking.png"), err)
        self.assertEqual(sorted(os.listdir(figs)), ["fig14_estimators_paper.png", "photo.png"])

    def test_estimators_plot(self):
        series = write(self.path("out", "paper", "LP-MLADRC.csv"), SERIES)
        self.linked(series, "figs", "fig14_estimators_paper.png")
        self.refused("estimators_plot.py", [self.path("out"), self.path("figs"), "paper"], series)

    def test_replay_and_response_plot(self):
        d = self.path("replay")
        names = ("replay.csv", "spectrum.csv", "identification.csv", "step_response.csv", "freq_response.csv",
                 "noise_throttle.csv", "response_summary.csv")
        for name in names:
            write(os.path.join(d, name), "t_s\n")
        step = os.path.join(d, "step_response.csv")
        self.linked(step, "replay", "response_freq.png")
        self.refused("response_plot.py", [d], step)
        self.refused("replay_plot.py", [d], step)
        os.unlink(os.path.join(d, "response_freq.png"))
        replay = os.path.join(d, "replay.csv")
        os.link(replay, os.path.join(d, "replay_spectrum.png"))  # a hard link this time
        self.refused("replay_plot.py", [d], replay)

    def test_replay_plot_removes_the_views_of_an_earlier_replay(self):
        d = self.path("replay")
        cols = ["t_s"] + ["%s_cmd_%s" % (src, a) for src in ("LOG", "LADRC") for a in ("roll", "pitch", "yaw")]
        write(os.path.join(d, "replay.csv"), ",".join(cols) + "\n" + "".join(
            ",".join("%g" % (0.01 * k if i == 0 else 0.1 * ((k * (i + 1)) % 7)) for i in range(len(cols))) + "\n"
            for k in range(50)))
        cols = ["hz"] + ["%s_%s" % (src, a) for src in ("gyro_raw", "gyro", "LOG", "LADRC")
                         for a in ("roll", "pitch", "yaw")]
        write(os.path.join(d, "spectrum.csv"), ",".join(cols) + "\n" + "".join(
            ",".join("%g" % (k if i == 0 else 1.0 / k) for i in range(len(cols))) + "\n" for k in range(1, 20)))
        write(os.path.join(d, "identification.csv"), "axis,lines_hz\nroll,120\npitch,\nyaw,\n")
        for name in ("response_step.png", "response_freq.png", "response_noise.png"):
            write(os.path.join(d, name), b"the views of an earlier replay")
        rc, _, err = tool("replay_plot.py", d)  # this replay wrote no step_response.csv: no views
        self.assertEqual(rc, 0, err)
        pngs = sorted(n for n in os.listdir(d) if n.endswith(".png"))
        self.assertEqual(pngs, ["replay_commands.png", "replay_spectrum.png"], err)

    def test_campaign(self):
        out = self.path("camp")
        plan = write(os.path.join(out, "plan.csv"), "run,tone\n1,0.5\n")
        write(os.path.join(out, "runs", "00001", "metrics.csv"), METRICS)
        self.linked(plan, "camp", "campaign.csv")
        self.refused("campaign.py", ["merge", out], plan)
        os.unlink(os.path.join(out, "campaign.csv"))
        import campaign_test
        table = write(os.path.join(out, "campaign.csv"), campaign_test.EXPECTED_SMALL)
        os.makedirs(os.path.join(out, "figures"))
        os.link(table, os.path.join(out, "figures", "tunemap.png"))
        for command in ("plot", "ratio", "tunemap"):
            self.refused("campaign.py", [command, out], table)

    def test_campaign_merge_removes_the_figures_of_the_table_it_replaces(self):
        import campaign_test
        out = self.path("camp")
        campaign_test.write_out(out, *campaign_test.small_campaign())
        for name in ("map_roll_tone_x.png", "rms_roll.png", "ratio_roll_tone_x.png", "tunemap.png", "mine.png"):
            write(os.path.join(out, "figures", name), b"drawn from the earlier table")
        rc, _, err = tool("campaign.py", "merge", out)
        self.assertEqual(rc, 0, err)
        self.assertEqual(os.listdir(os.path.join(out, "figures")), ["mine.png"])
        with open(os.path.join(out, "campaign.csv")) as f:
            self.assertEqual(f.read(), campaign_test.EXPECTED_SMALL)

    def test_log_ident_check(self):
        sil = write(self.path("bin", "ladrc_sil"), "#!/bin/sh\nexit 1\n")
        replay = write(self.path("bin", "ladrc_replay"), "#!/bin/sh\nexit 1\n")
        out = self.path("ident")  # not made: a refusal makes nothing
        for target in (sil, replay):
            self.refused("log_ident_check.py", ["--sil", sil, "--replay", replay, "--out", out, "--n", "1",
                                                "--markdown", target], target)
        # a scenario it writes and flies
        self.refused("log_ident_check.py", ["--sil", sil, "--replay", replay, "--out", out, "--n", "1",
                                            "--markdown", os.path.join(out, "af00_chirp.ini")],
                     os.path.join(out, "af00_chirp.ini"))

    def test_flight_logs_doc(self):
        check = write(self.path("logs", "check.md"), "summary\n")
        self.refused("flight_logs_doc.py", [self.path("logs"), check], check)


if __name__ == "__main__":
    unittest.main(verbosity=1)
