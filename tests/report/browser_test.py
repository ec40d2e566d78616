#!/usr/bin/env python3
"""The HTML report in a real browser (ctest label `browser`; docs/formats.md, "The HTML report").

Runs `delcert-certify --report` on a REFUTED GUDHI complex (fixtures/report/), opens the page in
headless Chromium with every network request refused, and checks that
  * the page rendered: the page's own pixel count after drawing (#render-status, read with
    --dump-dom) and a screenshot, decoded here, with non-background pixels and pixels in the
    witness colour inside the canvas;
  * the witness list of the page is the certificate's (check, kind, vertices, in order), and the
    page's data holds the same witnesses;
  * the report is written again with the same bytes;
  * the checks table lists the REFUTED checks first, then UNDECIDED, then CERTIFIED (then REPORT);
  * the margins column reads as numbers and words, never as raw JSON ({, ", : pairs);
  * the render counters are for this test only: #render-status is hidden and holds no text, and no
    text of the page reads like a debug counter ("pixels drawn");
  * each histogram with a certified bound has no estimate beyond it (data-beyond 0, data-min or
    data-max within the bound) and shows the bound next to it;
  * the T^2 in R^4 opens in the angle projection: #viewer's data-projection is "torus" and its first
    vertices are ((R + r cos phi) cos theta, (R + r cos phi) sin theta, r sin phi) with
    theta = atan2(x2, x1), phi = atan2(x4, x3), R = 1, r = 0.45, computed here from the points file;
  * a copy of the page whose thickness bound is raised above the estimates shows the contradiction
    as an error (data-beyond > 0 and a visible ERROR), not clipped.
Exit 77 (ctest SKIP_RETURN_CODE) when Chromium is not installed: skipped, not passed.

usage: browser_test.py CERTIFY FIXTURES WORKDIR
"""
import html
import json
import math
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

SKIP = 77


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def find_chromium():
    for name in (os.environ.get("DELCERT_CHROMIUM", ""), "chromium", "chromium-browser", "google-chrome"):
        if name and shutil.which(name):
            return shutil.which(name)
    return None


def read_png(path):
    """(width, height, rows of RGB(A) tuples) of an 8-bit RGB or RGBA PNG."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        fail(path + " is not a PNG")
    pos, idat, width = 8, b"", 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or colour not in (2, 6) or interlace:
                fail("unexpected PNG format (depth %d, colour type %d, interlace %d)" % (depth, colour, interlace))
            channels = 3 if colour == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, previous, at = [], bytearray(stride), 0
    for _ in range(height):
        kind, line = raw[at], bytearray(raw[at + 1:at + 1 + stride])
        at += 1 + stride
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b = previous[i]
            c = previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        previous = line
    return width, height, channels, rows


def witness_vertices(w):
    """The vertices a witness is about, by the rule of report/html_report.cpp (witness_simplex)."""
    def indices(x):
        return isinstance(x, list) and x and all(isinstance(i, int) and not isinstance(i, bool) and i >= 0 for i in x)
    if isinstance(w, dict):
        for key in ("simplex", "face", "ridge", "pair", "edge", "vertices"):
            if indices(w.get(key)):
                return w[key]
        for key in ("point", "vertex", "at_point", "at_vertex"):
            if isinstance(w.get(key), int) and not isinstance(w.get(key), bool) and w[key] >= 0:
                return [w[key]]
    return []


def chromium(browser, profile, *args):
    # Every host resolves to nothing and no proxy is reachable: the page must need no network.
    cmd = [browser, "--headless", "--no-sandbox", "--disable-gpu", "--use-angle=swiftshader",
           "--enable-unsafe-swiftshader", "--no-first-run", "--disable-extensions", "--user-data-dir=" + profile,
           "--host-resolver-rules=MAP * ~NOTFOUND", "--proxy-server=127.0.0.1:9", "--window-size=1280,1000",
           "--virtual-time-budget=15000", *args]
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=90)
    if r.returncode != 0:
        fail("chromium exited with %d: %s" % (r.returncode, r.stderr.decode(errors="replace")[-2000:]))
    return r.stdout.decode("utf-8", errors="replace")


def visible_text(fragment):
    return html.unescape(re.sub(r"<[^>]*>", " ", fragment))


def check_page(dom, certificate, points_path):
    # The table: REFUTED first, then UNDECIDED, CERTIFIED, the rest; by id within each.
    body = re.search(r'<table id="checks">.*?<tbody>(.*?)</tbody>', dom, re.S).group(1)
    rows = re.findall(r'<tr id="check-(\d+)" class="verdict-([A-Z]+)">(.*?)</tr>', body, re.S)
    if len(rows) != len(certificate["checks"]):
        fail("the table has %d rows, the certificate %d checks" % (len(rows), len(certificate["checks"])))
    rank = {"REFUTED": 0, "UNDECIDED": 1, "CERTIFIED": 2}
    order = [(rank.get(c["verdict"], 3), c["id"]) for c in certificate["checks"]]
    if [(rank.get(v, 3), int(i)) for i, v, _ in rows] != sorted(order):
        fail("the table is not ordered REFUTED, UNDECIDED, CERTIFIED: " + " ".join(v for _, v, _ in rows))
    if rows[0][1] != "REFUTED":
        fail("the first row of a refuted certificate's table is " + rows[0][1])
    # Margins: numbers a person reads, no JSON.
    margins = [visible_text(re.search(r'<td class="margin">(.*?)</td>', r, re.S).group(1)) for _, _, r in rows]
    for text in margins:
        if re.search(r'[{}"]|\[\s*"|"\s*:', text):
            fail("raw JSON in the margins column: " + text)
        if re.search(r"\.\d*[1-9]\d{4}", text):
            fail("a margin printed with all its digits: " + text)
    thickness = next(m for (i, _, _), m in zip(rows, margins) if int(i) == 5)
    if "dimension 2: faces 190, min thickness" not in thickness or "0.186 (certified)" not in thickness:
        fail("the thickness margin reads: " + thickness)
    print("table: %s first; margins e.g. '%s'" % (rows[0][1], thickness.strip()))
    # No debug counter on the page.
    status = re.search(r'<div id="render-status"([^>]*)>(.*?)</div>', dom, re.S)
    if not status or " hidden" not in status.group(1) or status.group(2).strip():
        fail("#render-status is visible or holds text: " + (status.group(0) if status else "missing"))
    if re.search(r"pixels drawn|in the witness colour", visible_text(re.sub(r"<script.*?</script>", "", dom, flags=re.S))):
        fail("the page shows a debug counter")
    # Histograms: within their certified bounds, the bound shown.
    bounded = 0
    for attrs_text, inner in re.findall(r'<div class="hist"([^>]*)>(.*?)(?=<div class="hist"|<h2>)', dom, re.S):
        a = dict(re.findall(r'data-([a-z]+)="([^"]*)"', attrs_text))
        if "bound" not in a:
            continue
        bounded += 1
        bound = float(a["bound"])
        if a.get("quantity") == "protection":
            if "certified minimum" not in visible_text(inner):
                fail("the protection bound is not shown: " + visible_text(inner))
            continue
        if a["beyond"] != "0" or "contradiction" in inner:
            fail("histogram %s: %s estimates beyond the certified bound" % (a["quantity"], a["beyond"]))
        if (a["side"] == "lower" and float(a["min"]) < bound) or (a["side"] == "upper" and float(a["max"]) > bound):
            fail("histogram %s shows a value beyond its bound %s: %s" % (a["quantity"], bound, a))
        if "certified" not in visible_text(inner):
            fail("histogram %s does not show its certified bound" % a["quantity"])
    if bounded < 3:
        fail("only %d histograms carry a certified bound (thickness, radius, protection expected)" % bounded)
    # The flat torus in its angle coordinates.
    viewer = re.search(r'<div id="viewer"([^>]*)>', dom).group(1)
    a = dict(re.findall(r'data-([a-z]+)="([^"]*)"', viewer))
    if a.get("projection") != "torus":
        fail("the T^2 in R^4 opens in projection %r, not the angle projection" % a.get("projection"))
    shown = json.loads(html.unescape(a["vertices"]))
    lines = [l.split() for l in open(points_path) if l.strip() and not l.startswith("#")][2:]
    expected = []
    for x in lines[:len(shown) // 3]:
        x1, x2, x3, x4 = map(float, x)
        theta, phi = math.atan2(x2, x1), math.atan2(x4, x3)
        expected += [(1 + 0.45 * math.cos(phi)) * math.cos(theta), (1 + 0.45 * math.cos(phi)) * math.sin(theta),
                     0.45 * math.sin(phi)]
    if len(shown) < 9 or any(abs(s - e) > 1e-5 for s, e in zip(shown, expected)):
        fail("the page's torus vertices %s are not the angle projection %s" % (shown[:6], expected[:6]))
    print("projection: torus of revolution by the angles; %d vertices compared" % (len(shown) // 3))


def main():
    if len(sys.argv) != 4:
        print(__doc__)
        return 2
    certify, fixtures, work = sys.argv[1:]
    browser = find_chromium()
    if not browser:
        print("SKIP: no chromium on PATH (Debian package chromium; scripts/setup.sh installs it): "
              "the HTML report was not opened in a browser")
        return SKIP
    os.makedirs(work, exist_ok=True)
    cert, page = os.path.join(work, "certificate.json"), os.path.join(work, "report.html")
    cmd = [certify, "--manifold", "builtin:clifford-torus-2",
           "--points", os.path.join(fixtures, "report", "clifford-torus-net.txt"),
           "--complex", os.path.join(fixtures, "report", "clifford-torus-gudhi.complex"),
           "--out", cert, "--report", page, "--no-times", "--threads", "2"]
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=120)
    if r.returncode == 2 and b"three.js" in r.stderr:
        fail("this build has no three.js: " + r.stderr.decode())
    if r.returncode != 1:
        fail("expected REFUTED (exit 1), got %d: %s %s" % (r.returncode, r.stdout.decode(), r.stderr.decode()))
    certificate = json.load(open(cert))
    with open(page, "rb") as f:
        first = f.read()
    os.remove(page)
    subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=120)
    with open(page, "rb") as f:
        if f.read() != first:
            fail("the same inputs gave a different report")

    expected = [(c["id"], w.get("kind", "") if isinstance(w, dict) else "", witness_vertices(w))
                for c in certificate["checks"] for w in c["witnesses"]]
    refuted = [c["id"] for c in certificate["checks"] if c["verdict"] == "REFUTED"]
    if certificate["verdict"] != "REFUTED" or not refuted:
        fail("the fixture is not refuted")
    if not any(e[0] in refuted and e[2] for e in expected):
        fail("no refuted check has a witness simplex")

    with tempfile.TemporaryDirectory() as profile:
        dom = chromium(browser, profile, "--dump-dom", "file://" + os.path.abspath(page))
    check_page(dom, certificate, os.path.join(fixtures, "report", "clifford-torus-net.txt"))
    status = re.search(r'<div id="render-status"([^>]*)>', dom)
    if not status:
        fail("no #render-status in the DOM")
    attrs = dict(re.findall(r'data-([a-z]+)="([^"]*)"', status.group(1)))
    if attrs.get("rendered") != "yes":
        fail("the page did not render: " + dom[status.start():status.start() + 300])
    nonblank, highlighted = int(attrs["nonblank"]), int(attrs["highlighted"])
    print("page: %s pixels drawn, %s in the witness colour" % (nonblank, highlighted))
    if nonblank < 2000 or highlighted < 50:
        fail("too few pixels drawn (%d) or highlighted (%d)" % (nonblank, highlighted))

    shown = []
    for m in re.finditer(r'<li class="witness [^"]*"([^>]*)>', dom):
        a = dict(re.findall(r'data-([a-z]+)="([^"]*)"', m.group(1)))
        shown.append((int(a["check"]), html.unescape(a["kind"]), json.loads(html.unescape(a["simplex"]))))
    if shown != expected:
        fail("the page lists %d witnesses, the certificate %d; first difference: %s" % (
            len(shown), len(expected), next(((s, e) for s, e in zip(shown, expected) if s != e), None)))
    data = json.loads(re.search(r'<script type="application/json" id="delcert-data">(.*?)</script>', dom, re.S).group(1))
    if [w["witness"] for w in data["witnesses"]] != [w for c in certificate["checks"] for w in c["witnesses"]]:
        fail("the page's data does not hold the certificate's witnesses")
    print("witnesses: %d listed, as in the certificate (refuted checks %s)" % (len(shown), refuted))

    # A certified bound the page's estimates contradict (the thickness bound raised above the
    # thinnest simplex, in a copy of the page's data) is shown as an error, not clipped away.
    with open(page, encoding="utf-8") as f:
        text = f.read()
    block = re.search(r'(<script type="application/json" id="delcert-data">)(.*?)(</script>)', text, re.S)
    tampered = json.loads(block.group(2))
    tampered["margins"]["thickness"]["2"]["min_thickness"]["certified_lower_bound"] = "0.3"
    bad_page = os.path.join(work, "report-contradiction.html")
    with open(bad_page, "w", encoding="utf-8") as f:
        f.write(text[:block.start(2)] + json.dumps(tampered).replace("<", "\\u003c") + text[block.end(2):])
    with tempfile.TemporaryDirectory() as profile:
        bad_dom = chromium(browser, profile, "--dump-dom", "file://" + os.path.abspath(bad_page))
    hist = re.search(r'<div class="hist"([^>]*data-quantity="thickness"[^>]*)>(.*?)(?=<div class="hist"|<h2>)', bad_dom, re.S)
    if not hist:
        fail("no thickness histogram in the tampered page")
    a = dict(re.findall(r'data-([a-z]+)="([^"]*)"', hist.group(1)))
    if int(a.get("beyond", "0")) == 0 or 'class="contradiction"' not in hist.group(2) or "ERROR" not in hist.group(2):
        fail("estimates below a certified lower bound are not shown as an error: " + hist.group(0)[:400])
    print("contradiction: %s thickness estimates below a raised bound, shown as an error" % a["beyond"])

    shot = os.path.join(work, "report.png")
    with tempfile.TemporaryDirectory() as profile:
        chromium(browser, profile, "--screenshot=" + shot, "file://" + os.path.abspath(page))
    width, height, channels, rows = read_png(shot)
    x0, y0, w, h = (int(v) for v in attrs["canvas"].split(","))
    if not (w > 100 and h > 100 and x0 + w <= width and y0 + h <= height):
        fail("the canvas (%s) is not inside the %dx%d screenshot" % (attrs["canvas"], width, height))
    drawn = red = 0
    for y in range(y0 + 2, y0 + h - 2):
        row = rows[y]
        for x in range(x0 + 2, x0 + w - 2):
            p = row[x * channels:x * channels + 3]
            if p[0] < 245 or p[1] < 245 or p[2] < 245:
                drawn += 1
            if p[0] > 150 and p[1] < 90 and p[2] < 90:
                red += 1
    print("screenshot: %d non-background pixels in the canvas, %d in the witness colour" % (drawn, red))
    if drawn < 2000 or red < 50:
        fail("the screenshot shows too little of the mesh (%d pixels) or of the witnesses (%d)" % (drawn, red))
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
