"""Drives `radflux view`'s page in headless Chromium (chromium-driver, python3-selenium).

Usage: view_browser.py URL DIR START_CMD RESULT_CMD   (a job's view)
       view_browser.py --glb URL                     (`radflux view RESULT.glb`: the saved
                                                      result shows the box's coloured walls)
       view_browser.py --lightmap LM_URL VC_URL      (`radflux view` of one solve's lightmapped
                                                      GLB and of its vertex-coloured GLB)
  URL         the page of a job that is still queued;
  START_CMD   a shell command that lets the job start (cancels the job ahead of it), run once
              the page is up, so the page sees the job from its first snapshot;
  RESULT_CMD  a shell command writing the job's final B to DIR/final.csv and its lit mesh to
              DIR/final.glb (radflux result).
Checks, from window.radfluxView and screenshots: snapshots arrive and a later one is closer
to the final B than the first; the colours shown change; the residual plot has every point;
the page's last B is the final B (float16); the report and the GLB link appear, the link's
bytes are `radflux result --out`'s; the final screenshot shows the Cornell box's red and
green walls and is closer to the later screenshot than to the first; the job list (/jobs/)
links the job. Saves DIR/mid_solve.png. Waits on conditions only."""
import csv
import io
import subprocess
import sys
import time
import urllib.request

from PIL import Image, ImageChops, ImageStat
from selenium import webdriver
from selenium.webdriver.chrome.service import Service

TIMEOUT = 120  # seconds for any one condition: generous, never a measure


def wait_for(driver, expression, what):
    deadline = time.monotonic() + TIMEOUT
    while time.monotonic() < deadline:
        value = driver.execute_script("return " + expression)
        if value:
            return value
        time.sleep(0.05)
    sys.exit(f"timed out waiting for {what}: {driver.execute_script('return window.radfluxView')}")


def state(driver):
    return driver.execute_script(
        "const v = window.radfluxView; return {iteration: v.snapshots[v.snapshots.length - 1],"
        " b: Array.from(v.radiosity), colours: Array.from(v.colours)};")


def scene_shot(driver, save_as=None):
    """The 3D part of a screenshot (the canvas), as RGB; the whole page saved as `save_as`
    (a 64-colour PNG, small enough for the README)."""
    png = driver.get_screenshot_as_png()
    width = driver.execute_script("return document.querySelector('#scene canvas').clientWidth")
    image = Image.open(io.BytesIO(png)).convert("RGB")
    if save_as:
        image.quantize(64).save(save_as, optimize=True)
    return image.crop((0, 0, width, image.height))


def distance(b, final):
    """Mean |b - final| over patches and bands, relative to the mean of final."""
    return sum(abs(x - y) for x, y in zip(b, final)) / sum(final)


def image_distance(a, b):
    return sum(ImageStat.Stat(ImageChops.difference(a, b)).mean)


def check(condition, message):
    if not condition:
        sys.exit("FAILED: " + message)


def colour_walls(shot):
    """Fractions of clearly red and clearly green pixels."""
    pixels = list(shot.getdata())
    red = sum(1 for r, g, b in pixels if r > g + 40 and r > b + 40) / len(pixels)
    green = sum(1 for r, g, b in pixels if g > r + 40 and g > b + 40) / len(pixels)
    print(f"screenshot: {red:.1%} red, {green:.1%} green pixels")
    return red > 0.01 and green > 0.01


def browser():
    options = webdriver.ChromeOptions()
    for flag in ("--headless=new", "--no-sandbox", "--disable-gpu", "--use-angle=swiftshader",
                 "--enable-unsafe-swiftshader", "--window-size=1100,700",
                 "--disable-dev-shm-usage"):
        options.add_argument(flag)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    options.binary_location = "/usr/bin/chromium"
    return webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)


def saved_result(url):
    driver = browser()
    try:
        driver.get(url)
        wait_for(driver, "window.radfluxView && (radfluxView.ready || radfluxView.error)",
                 "the saved result")
        check(not driver.execute_script("return radfluxView.error"), "the GLB did not load")
        check(colour_walls(scene_shot(driver)), "the saved result lacks the red and green walls")
    finally:
        driver.quit()


def job_view(url, scratch, start_cmd, result_cmd):
    driver = browser()
    try:
        driver.get(url)
        wait_for(driver, "window.radfluxView && radfluxView.ready && "
                 "radfluxView.state === 'JOB_STATE_QUEUED'", "the page, its job queued")
        subprocess.run(start_cmd, shell=True, check=True, stdout=subprocess.DEVNULL)
        wait_for(driver, "radfluxView.snapshots.length >= 1", "a first snapshot")
        first, first_shot = state(driver), scene_shot(driver)
        wait_for(driver, f"radfluxView.snapshots[radfluxView.snapshots.length - 1] >= "
                 f"{first['iteration']} + 3", "a later snapshot")
        later, later_shot = state(driver), scene_shot(driver, f"{scratch}/mid_solve.png")
        wait_for(driver, "radfluxView.ended && radfluxView.snapshots.length >= 3 && "
                 "document.getElementById('report').textContent.includes('{')",
                 "the job's end and its report")
        final_page = state(driver)
        final_shot = scene_shot(driver)
        check(driver.execute_script("return !!document.querySelector('a[href=\"result.glb\"]')"),
              "no download link for the lit mesh")
        plot = driver.execute_script("return [radfluxView.plotPoints, radfluxView.residuals]")
        check(plot[0] >= 3 and plot[0] == len(plot[1]), f"residual plot points {plot[0]}")
        check(plot[1][-1][1] < plot[1][0][1], "residuals did not fall")
        job_id = url.rstrip("/").split("/")[-1]
        driver.get(url.split("/job/")[0] + "/jobs/")
        wait_for(driver, f"document.querySelector('a[href=\"/job/{job_id}/\"]')",
                 "the job list linking the job")
    finally:
        driver.quit()
    subprocess.run(result_cmd, shell=True, check=True, stdout=subprocess.DEVNULL)
    with urllib.request.urlopen(url + "result.glb") as r, open(f"{scratch}/final.glb", "rb") as f:
        check(r.read() == f.read(), "the page's lit mesh differs from `radflux result --out`")
    with open(f"{scratch}/final.csv") as f:
        final = [float(row[k]) for row in csv.DictReader(f) for k in ("r", "g", "b")]
    d_first, d_later = distance(first["b"], final), distance(later["b"], final)
    d_end = distance(final_page["b"], final)
    print(f"snapshots at iterations {first['iteration']}, {later['iteration']}, "
          f"{final_page['iteration']}; distance to the final B {d_first:.4f}, {d_later:.4f}, "
          f"{d_end:.5f}")
    check(len(first["b"]) == len(final), "snapshot and result patch counts differ")
    check(d_later < d_first, "the later snapshot is not closer to the final B than the first")
    check(d_end < 2e-3, f"the page's last B is not the final B (float16): {d_end}")
    check(max(abs(a - b) for a, b in zip(first["colours"], later["colours"])) > 1 / 255,
          "the colours shown did not change")
    check(colour_walls(final_shot), "the final screenshot lacks the red and green walls")
    s_first, s_later = image_distance(first_shot, final_shot), image_distance(later_shot, final_shot)
    print(f"screenshot distance to the final: first {s_first:.2f}, later {s_later:.2f}")
    check(s_later < s_first, "the later screenshot is not closer to the final than the first")


def shown_glb(driver, url):
    """The canvas of `radflux view RESULT.glb` once loaded, how many meshes the page drew with
    the baked lightmap and its emissive strength; fails on a load error or a console error."""
    driver.get(url)
    wait_for(driver, "window.radfluxView && (radfluxView.ready || radfluxView.error)", url)
    check(not driver.execute_script("return radfluxView.error"), f"{url} did not load")
    errors = [e["message"] for e in driver.get_log("browser") if e["level"] == "SEVERE"
              and "/favicon.ico " not in e["message"]]  # the browser's own ask, not the page's
    check(not errors, f"console errors at {url}: {errors}")
    return scene_shot(driver), driver.execute_script(
        "return [radfluxView.lightmapped, radfluxView.lightmapStrength]")


def lightmap_against_vertex_colours(lightmap_url, vertex_url):
    """The lightmapped GLB is drawn with its baked texture: three.js shows the same picture as
    the vertex-coloured GLB of the same solve (the lightmap holds the same interpolated vertex
    radiosity at the same scale) within the texture's quantisation, over all scene pixels.
    The texture holds radiance / S (S, the emissive strength, keeps the lamp above 1), so one
    texel code is about S^(1/2.4) codes on the screen (sRGB both ways): half of it, plus a
    code of rounding, is the tolerance q; the median must be within q, the 95th percentile
    within 2q. A wrong UV set or a missing emissive strength fails this by far."""
    driver = browser()
    try:
        lightmap, (charts, strength) = shown_glb(driver, lightmap_url)
        vertex, (plain, _) = shown_glb(driver, vertex_url)
    finally:
        driver.quit()
    check(charts >= 1 and plain == 0, f"meshes drawn with a lightmap: {charts} and {plain}")
    check(colour_walls(lightmap), "the lightmapped result lacks the red and green walls")
    background = (16, 17, 20)  # 0x101114, the scene's background
    diffs = sorted(max(abs(a - b) for a, b in zip(p, q))
                   for p, q in zip(lightmap.getdata(), vertex.getdata())
                   if q != background or p != background)
    median, p95 = diffs[len(diffs) // 2], diffs[int(0.95 * len(diffs))]
    q = 0.5 * strength ** (1 / 2.4) + 1
    print(f"lightmap (strength {strength:.1f}, q {q:.1f} codes) vs vertex colours over "
          f"{len(diffs)} pixels: |difference| (8-bit codes) median {median}, 95th percentile "
          f"{p95}, max {diffs[-1]}")
    check(median <= q and p95 <= 2 * q,
          "the lightmapped picture differs from the vertex-coloured one beyond quantisation")


if sys.argv[1] == "--glb":
    saved_result(sys.argv[2])
elif sys.argv[1] == "--lightmap":
    lightmap_against_vertex_colours(sys.argv[2], sys.argv[3])
else:
    job_view(*sys.argv[1:5])
