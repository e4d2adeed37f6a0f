"""Every command's --json reports the parameters the library used, equal to the defaults its --help documents.

For each command, run with only its required arguments and --json; every option whose --help text states a
literal default ("(default 315)", "default 0.5", "fft (default)", "(default: both)") must appear in the JSON
under its name (dashes as underscores, or the alias below) with that value. An option whose default is prose
("the first", "from the extent") is not checked: there is no literal to compare. Options that are not
parameters of the computation (input selection, output format, threads, stripes) are listed in NOT_REPORTED
with the reason.
"""
import csv
import math
import re

import pytest

VOLCANO = "dem_volcano_maunga_whau_10m.tif"
LUX = "dem_luxembourg_utm32n.tif"
SKYE = "gshhg_skye_utm29n.geojson"
STATES = "dcw_us_states_small_albers5070.geojson"
SEED = "seed_contour_volcano.geojson"
DAVIS = "points_mass_topo_davis1973.csv"

# Options that select input or shape the run, not a parameter of the method: not in the JSON. Options given
# on a command's argv below are not compared with their defaults. An option that only acts with another
# (a seed of random points that are drawn only with --pairs or --sample) is reported only then: CONDITIONAL.
NOT_REPORTED = {
    "--band": "which band is read (the input)",
    "--layer": "which layer is read (the input)",
    "--format": "the output driver",
    "--tile-rows": "stripes give the whole run's cells",
    "--threads": "cells do not depend on it",
    "--x/--y/--z": "input columns",
    "--view": "reported as view",
}
CONDITIONAL = {  # {command: {option: the option without which it does not act}}
    ("dim", "surface"): {"--seed": "--pairs"},
    ("dim", "map"): {"--seed": "--pairs"},
    ("dim", "points"): {"--seed": "--sample"},
    ("mountain",): {"--summit": "--dem"},
}

# Each command: argv after the command (data file names resolved) and JSON key aliases {option: key}
# (a dotted key names a member of an object).
COMMANDS = [
    (["hillshade"], ["@" + VOLCANO, "{tmp}/hs.tif"], {}),
    (["render"], ["@" + VOLCANO, "{tmp}/r.png", "--view", "perspective"], {}),
    (["synth"], ["{tmp}/s.tif", "--dim", "2.3", "--size", "64x64"], {}),
    (["smooth"], ["@" + SKYE, "{tmp}/sm.geojson"], {}),
    (["enhance"], ["@" + SKYE, "{tmp}/en.geojson"], {}),
    (["boundary"], ["@" + SKYE, "{tmp}/bo.geojson", "--dim", "1.2"], {}),
    (["simplify"], ["@" + SKYE, "{tmp}/si.geojson", "--tolerance", "100"], {}),
    (["weed"], ["@" + SKYE, "{tmp}/we.geojson", "--min-segment", "100"], {}),
    (["mountain"], ["@" + SEED, "{tmp}/mo.geojson", "--dem", "{tmp}/mo.tif"], {"--summit": "dem.summit"}),
    (["dim", "line"], ["@" + SKYE], {}),
    (["dim", "area"], ["@" + STATES], {}),
    (["dim", "points"], ["@" + DAVIS, "--min-pairs", "3"], {}),  # 52 points: too few for 100 pairs a lag
    (["dim", "surface"], ["@" + VOLCANO], {}),
    (["dim", "map"], ["@" + VOLCANO, "{tmp}/dm.tif", "--window", "16"], {}),
    (["dim", "map"], ["@" + VOLCANO, "{tmp}/dm2.tif", "--window", "16", "--pairs", "200"], {}),
    (["dim", "profile"], ["@" + VOLCANO, "--row", "40"], {}),
    (["fill"], ["@" + LUX, "{tmp}/fi.tif"], {}),
    (["mountain"], ["@" + SEED, "{tmp}/mm.geojson", "--method", "midpoint"], {}),
    (["mountain"], ["@" + SEED, "{tmp}/mf.geojson", "--method", "fourier"], {}),
    (["reconstruct"], ["@" + LUX, "{tmp}/re.tif"], {}),  # the voids of a DEM: D and sigma0 from its cells
    (["urban", "table"], ["@" + STATES, "--class", "code"], {}),
    (["model", "fit"], ["@" + VOLCANO, "-o", "{tmp}/model.json"],
     {"--cutoff": "harmonics.cutoff", "--min-wavelength": "regression.min_wavelength_cells"}),
]

NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:,[-+]?(?:\d+\.?\d*|\.\d+))*|inf"


def option_blocks(help_text):
    """{'--name': text of its line and continuation lines} from the Options section of --help."""
    blocks, current = {}, None
    for line in help_text.splitlines():
        m = re.match(r"^\s+(?:-\w, )?(--[\w/-]+(?:/--[\w-]+)*)", line)
        if m:
            current = m.group(1)
            blocks[current] = line[m.end():]
        elif current and line.startswith("      ") and line.strip():
            blocks[current] += " " + line.strip()
        else:
            current = None
    return blocks


def literal_default(text):
    """The literal default a help text states, as a string, or None when there is none (or only prose)."""
    m = re.search(r"([\w.-]+) \(default\)", text)
    if m:
        return m.group(1)
    m = re.search(r"default:?\s+(" + NUMBER + r")(?=[\s);:]|$)", text)
    if m:
        return m.group(1)
    m = re.search(r"default:\s+(\w+)\)", text)
    if m:
        return m.group(1)
    m = re.search(r"; default (\w+)$", text.strip())
    if m:
        return m.group(1)
    return None


def method_default(text, method):
    """The default a help text states for one method ("3 for improved, 1.4 for midpoint and fourier"), or None."""
    m = re.search(r"(" + NUMBER + r") for (?:\w+ and )?" + re.escape(method) + r"\b", text)
    return m.group(1) if m else None


def acts_with_method(text, method_help, args):
    """False when an option's help begins with the methods it acts with ("fourier, improved: ...") and the run's
    --method (or the default method, when none is given) is not one of them. The words count as methods only
    when --method's own help names each of them."""
    m = re.match(r"\s*(?:\S+\s{2,})?((?:\w+, )*\w+): ", text)  # after the metavar, if any
    if not m:
        return True
    methods = m.group(1).split(", ")
    if not all(re.search(r"\b%s\b" % w, method_help) for w in methods):
        return True
    if "--method" in args:
        return args[args.index("--method") + 1] in methods
    d = re.search(r"(\w+) \(default\)", method_help)
    return d is None or d.group(1) in methods


def same(reported, documented):
    if documented == "inf":
        return reported is None or reported == math.inf
    if documented == "none":
        return reported is None or reported == "none"
    if re.fullmatch(NUMBER, documented):
        want = [float(v) for v in documented.split(",")]
        got = reported if isinstance(reported, list) else [reported]
        if isinstance(reported, bool) or not all(isinstance(v, (int, float)) for v in got):
            return False
        return len(got) == len(want) and all(abs(g - w) <= 1e-12 * max(1.0, abs(w)) for g, w in zip(got, want))
    return str(reported).lower() == documented.lower()


@pytest.mark.parametrize("words,args,aliases", COMMANDS, ids=[" ".join(c[0]) for c in COMMANDS])
def test_json_reports_the_documented_defaults(cli, data, tmp_path, words, args, aliases):
    help_text = cli(*words, "--help", json_out=False)
    argv = [data(a[1:]) if a.startswith("@") else a.format(tmp=tmp_path) for a in args]
    report = cli(*words, *argv)
    checked, drifts = 0, []
    blocks = option_blocks(help_text)
    for opt, text in blocks.items():
        doc = (method_default(text, args[args.index("--method") + 1]) if "--method" in args else None) \
            or literal_default(text)
        if doc is None or opt in NOT_REPORTED or opt in ("--help", "--json") or opt in args:
            continue
        needs = CONDITIONAL.get(tuple(words), {}).get(opt)
        if needs is not None and needs not in args:
            continue
        if not acts_with_method(text, blocks.get("--method", ""), args):
            continue
        key = aliases.get(opt, opt.lstrip("-").replace("-", "_"))
        checked += 1
        where = report
        for part in key.split(".")[:-1]:
            where = where.get(part) if isinstance(where, dict) else None
        key = key.split(".")[-1]
        if not isinstance(where, dict) or key not in where:
            drifts.append("%s: --help documents default %s, the JSON has no %r" % (opt, doc, key))
        elif not same(where[key], doc):
            drifts.append("%s: --help documents default %s, the JSON reports %r" % (opt, doc, where[key]))
    assert not drifts, "fracterra %s:\n  " % " ".join(words) + "\n  ".join(drifts)
    # simplify and weed document no literal default (their one parameter is required)
    assert checked > 0 or words in (["simplify"], ["weed"]), "no documented default was checked"


def test_model_simulate(cli, data, tmp_path):
    """model simulate needs a model file: fitted first, then simulated with the defaults."""
    cli("model", "fit", data(VOLCANO), "-o", tmp_path / "m.json")
    test_json_reports_the_documented_defaults(cli, data, tmp_path, ["model", "simulate"],
                                              [str(tmp_path / "m.json"), "{tmp}/sim.tif"], {})


def test_urban_regress(cli, data, tmp_path):
    """urban regress needs a table: made by urban table first, then regressed with the defaults."""
    t = tmp_path / "t.csv"
    cli("urban", "table", data(STATES), data(STATES), data(STATES), "--class", "code", "--label", "1",
        "--label", "2", "--label", "3", "-o", t)
    rows = list(csv.reader(t.read_text().splitlines()))  # the three years made different: a line can be fitted
    d, area = rows[0].index("D"), rows[0].index("area")
    for i, row in enumerate(rows[1:]):
        row[d], row[area] = "%.3f" % (1.1 + 0.1 * i), "%.1f" % (1000.0 * (i + 1) ** 2)
    t.write_text("\n".join(",".join(r) for r in rows) + "\n")
    test_json_reports_the_documented_defaults(cli, data, tmp_path, ["urban", "regress"],
                                              [str(tmp_path / "t.csv")], {})


def test_parser_finds_the_defaults():
    """The help parser itself: literal defaults found, prose defaults not taken for literals."""
    assert literal_default("light direction (default 315)") == "315"
    assert literal_default("in (0,1]; default 0.5") == "0.5"
    assert literal_default("fft (default): spectral") == "fft"
    assert literal_default("madogram, variogram or both (default: both)") == "both"
    assert literal_default("angles (default 20,40;") == "20,40"
    assert literal_default("the vector layer to read (default: the first)") is None
    assert literal_default("largest scale; default: from the extent") is None
    assert literal_default("(default W / 4)") is None
    assert method_default("d' = K d (default 3 for improved, 1.4 for midpoint and fourier, 1.2 for simple)",
                          "fourier") == "1.4"
    assert method_default("(default 3 for improved, 1.4 for midpoint and fourier)", "improved") == "3"
    assert method_default("(default 3)", "improved") is None
    mh = "simple: shrink; midpoint: displace; improved (default): both"
    assert literal_default("the explanatory column; default D") == "D"
    assert not acts_with_method(" K   midpoint, improved: angles", mh, ["--method", "simple"])
    assert not acts_with_method(" midpoint, improved: angles", mh, ["--method", "simple"])
    assert acts_with_method(" midpoint, improved: angles", mh, ["--method", "midpoint"])
    assert acts_with_method(" midpoint, improved: angles", mh, [])
    assert acts_with_method(" alone: the bounding box", mh, ["--method", "simple"])
    assert same(315.0, "315") and not same(1.4, "1.2") and same([20.0, 40.0], "20,40") and same(None, "inf")
