"""python -m linkgi.web, driven in headless Chromium: a light move arrives as new colours.

Starts the trame app on a model (Testing/Data/Models/bunny-inward.vtp by default), opens
it in Debian's Chromium (fresh profile) and drives it through the DevTools protocol (its
websocket, with aiohttp, which trame brings): the page draws the lit model; moving the
lamp (as its slider does, through trame's state) makes the server relight and the browser
receive the new colours (the state's version), within a second of the light update's own
time; the drawn picture changes where the light moved; a click on the model moves the lamp
above the clicked point; and the server's baked colours follow the light (the side the lamp
moved to gets brighter).

Run by the Python of a virtual environment with trame (scripts/test.sh makes it):
  TestWebApp.py [output directory] [model]
"""
import asyncio
import base64
import json
import os
import re
import socket
import signal
import subprocess
import sys
import tempfile
import time

import aiohttp
import numpy as np

import linkgi_export_testing as testing
from vtkmodules.util.numpy_support import vtk_to_numpy

HERE = os.path.dirname(os.path.abspath(__file__))
MODEL = os.path.join(HERE, "..", "Data", "Models", "bunny-inward.vtp")


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class DevTools:
    """One page of a headless Chromium, driven over the DevTools protocol."""

    def __init__(self, websocket):
        self.ws = websocket
        self.next = 0
        self.session = None
        self.console = []  # the page's console messages and exceptions

    async def call(self, method, **params):
        self.next += 1
        message = {"id": self.next, "method": method, "params": params}
        if self.session:
            message["sessionId"] = self.session
        await self.ws.send_str(json.dumps(message))
        while True:
            reply = json.loads((await self.ws.receive()).data)
            if reply.get("method") == "Runtime.consoleAPICalled":
                self.console.append(" ".join(str(a.get("value", a.get("description", "")))
                                             for a in reply["params"]["args"]))
            elif reply.get("method") == "Runtime.exceptionThrown":
                self.console.append(str(reply["params"]["exceptionDetails"])[:300])
            if reply.get("id") == self.next:
                if "error" in reply:
                    raise RuntimeError(f"{method}: {reply['error']}")
                return reply["result"]

    async def open(self, url):
        target = await self.call("Target.createTarget", url=url)
        attached = await self.call("Target.attachToTarget", targetId=target["targetId"],
                                   flatten=True)
        self.session = attached["sessionId"]
        await self.call("Page.enable")
        await self.call("Runtime.enable")
        await self.call("Emulation.setDeviceMetricsOverride", width=900, height=560,
                        deviceScaleFactor=1, mobile=False)

    async def evaluate(self, expression):
        result = await self.call("Runtime.evaluate", expression=expression,
                                 returnByValue=True, awaitPromise=True)
        return result["result"].get("value")

    async def wait_for(self, expression, timeout=60.0):
        start = time.perf_counter()
        while time.perf_counter() - start < timeout:
            value = await self.evaluate(expression)
            if value:
                return value
            await asyncio.sleep(0.05)
        await self.screenshot(os.path.join(tempfile.gettempdir(), "linkgi-web-timeout.png"))
        state = await self.evaluate("JSON.stringify({trame: !!window.trame, "
                                    "canvas: document.querySelectorAll('canvas').length, "

                                    "body: document.body.innerText.slice(0, 200)})")
        raise AssertionError(f"timed out waiting for {expression}: {state}")

    async def screenshot(self, path):
        data = (await self.call("Page.captureScreenshot", format="png"))["data"]
        with open(path, "wb") as f:
            f.write(base64.b64decode(data))
        return path


async def drive(url, out, moved):
    # Chromium's helper processes may still write to the profile after the browser exits.
    with tempfile.TemporaryDirectory(ignore_cleanup_errors=True) as profile:
        browser = subprocess.Popen(
            ["chromium", "--headless=new", "--no-sandbox", "--use-gl=swiftshader",
             "--enable-unsafe-swiftshader", "--remote-debugging-port=0",
             f"--user-data-dir={profile}", "--no-first-run", "about:blank"],
            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, start_new_session=True)
        try:
            endpoint = None
            for line in browser.stderr:
                match = re.search(r"DevTools listening on (ws://\S+)", line)
                if match:
                    endpoint = match.group(1)
                    break
            assert endpoint, "Chromium did not open its DevTools endpoint"
            async with aiohttp.ClientSession() as http:
                async with http.ws_connect(endpoint, max_msg_size=0) as ws:
                    page = DevTools(ws)
                    await page.open(url)
                    await page.wait_for("window.trame && window.trame.state && "
                                        "window.trame.state.get('version') >= 0 && "
                                        "document.querySelector('canvas') !== null")
                    await asyncio.sleep(2.0)  # the first frame (the sliders may snap)
                    version = await page.evaluate("window.trame.state.get('version')")
                    before = testing.read_png(await page.screenshot(os.path.join(out, "web-before.png")))
                    x = await page.evaluate("window.trame.state.get('light_x')")
                    # Move the lamp to the other side along x, as its slider does.
                    start = time.perf_counter()
                    await page.evaluate(f"window.trame.state.set('light_x', {moved})")
                    await page.wait_for(f"window.trame.state.get('version') > {version}")
                    arrived = time.perf_counter() - start
                    light_ms = await page.evaluate("window.trame.state.get('light_ms')")
                    await asyncio.sleep(1.0)  # the new frame
                    after = testing.read_png(await page.screenshot(os.path.join(out, "web-after.png")))
                    # A click on the model (the view's middle) moves the lamp above it.
                    version = await page.evaluate("window.trame.state.get('version')")
                    for kind in ("mousePressed", "mouseReleased"):
                        await page.call("Input.dispatchMouseEvent", type=kind, x=610, y=320,
                                        button="left", clickCount=1)
                    await page.wait_for(f"window.trame.state.get('version') > {version}")
                    clicked = await page.evaluate("[window.trame.state.get('light_x'), "
                                                  "window.trame.state.get('light_y'), "
                                                  "window.trame.state.get('light_z')]")
                    return x, arrived, light_ms, before, after, clicked
        finally:
            os.killpg(browser.pid, signal.SIGTERM)  # the browser and its helpers
            browser.wait(timeout=30)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    model = sys.argv[2] if len(sys.argv) > 2 else MODEL
    os.makedirs(out, exist_ok=True)
    import linkgi.web as web
    surface = web.read_surface(model)
    bounds = surface.GetBounds()
    centre_x = 0.5 * (bounds[0] + bounds[1])
    port = free_port()
    scene = web.LiveScene(surface)
    lamp = scene.centre + np.array([0.3, 0.4, 0.8]) * scene.size * 0.6  # the app's start
    moved = 2 * centre_x - lamp[0]
    server = subprocess.Popen(
        [sys.executable, "-m", "linkgi.web", model, "--server", "--port", str(port)],
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        for line in server.stdout:
            if "App running at" in line:
                break
        else:
            raise AssertionError("the app did not start")
        x, arrived, light_ms, before, after, clicked = asyncio.run(
            drive(f"http://127.0.0.1:{port}/", out, moved))
    finally:
        server.terminate()
        server.wait(timeout=30)
    # The 3D view: right of the drawer, below the toolbar (the rest is the page's controls).
    view_before, view_after = before[80:, 320:], after[80:, 320:]
    background = np.median(view_before.reshape(-1, 3), axis=0)
    model = (np.abs(view_before.astype(int) - background).sum(axis=2) > 24).sum()
    changed = (np.abs(view_before.astype(int) - view_after.astype(int)).sum(axis=2) > 24).sum()
    print(f"lamp x {x:.3f} -> {moved:.3f}: new colours in the browser after {arrived:.3f} s "
          f"(the server's light update {light_ms} ms); the model covers {model} pixels of "
          f"the view, {changed} changed")
    assert model > 5000, "the view does not show the model"
    assert changed > 0.1 * model, "the view did not change when the lamp moved"
    assert arrived <= light_ms / 1000.0 + 1.0, f"new colours took {arrived:.2f} s"
    # The click put the lamp outside the model, a third of its size from the clicked point.
    lo, hi = np.array(bounds[0::2]), np.array(bounds[1::2])
    print(f"a click on the model put the lamp at {np.round(clicked, 3).tolist()}")
    assert clicked[0] != moved and not ((lo < clicked) & (clicked < hi)).all(), clicked

    # The server's colours follow the light: the side the lamp went to brightens.
    sides = []
    for position_x in (lamp[0], 2 * centre_x - lamp[0]):
        scene.place_lamp((position_x, lamp[1], lamp[2]))
        scene.set_method("links", 2)
        scene.relight()
        colors = scene.colors_of("combined").astype(float).sum(axis=1)
        xs = vtk_to_numpy(scene.baked.GetPoints().GetData())[:, 0]
        sides.append((colors[xs > centre_x].mean(), colors[xs < centre_x].mean()))
    (first_plus, first_minus), (second_plus, second_minus) = sides
    toward_plus = lamp[0] > centre_x
    assert (first_plus > first_minus) == toward_plus, sides
    assert (second_plus > second_minus) != toward_plus, sides
    print("ok")


if __name__ == "__main__":
    main()
