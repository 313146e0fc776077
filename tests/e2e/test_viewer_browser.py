"""The web viewer in headless Chromium against a real uvicorn server: enter the API key,
search, and check that the highlighted answer marker is the API's answer, in the plan
and in the 3D view (three.js on WebGL, rendered by SwiftShader on the CPU).

Needs Debian's ``chromium`` and ``chromium-driver`` (``.ci/run`` installs them); skips only
when they are missing. The screenshot goes to ``tests/artifacts/viewer.png`` or to the
folder named by ``INHERIT_SG_ARTIFACTS`` (the 3D view's to ``viewer3d.png`` beside it).
"""

from __future__ import annotations

import os
import shutil
from collections.abc import Iterator
from pathlib import Path

import httpx
import pytest
from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.by import By
from selenium.webdriver.common.keys import Keys
from selenium.webdriver.remote.webdriver import WebDriver
from selenium.webdriver.support import expected_conditions as ec
from selenium.webdriver.support.ui import WebDriverWait

from inherit_sg.api.app import create_app
from inherit_sg.config import Config, ServiceConfig
from inherit_sg.facade import build_map
from inherit_sg.ingest.synthetic.generate import generate_house, write_dataset
from tests.local_http import uvicorn_on_loopback

REPO_ROOT = Path(__file__).resolve().parents[2]
NAME = "viewer-house"
KEY = "viewer-read-key"
QUERY = "the sofa in the living room"
MANY = "a window"
WAIT_S = 60


def _find(*names: str) -> str | None:
    for name in names:
        found = shutil.which(name)
        if found:
            return found
    return None


CHROMIUM = _find("chromium", "chromium-browser")
DRIVER = _find("chromedriver")
MISSING = (
    "headless browser test needs Debian's chromium and chromium-driver "
    "(apt-get install chromium chromium-driver)"
)
# CI sets INHERIT_SG_REQUIRE_BROWSER=1 so that a missing browser fails instead of skipping
pytestmark = pytest.mark.skipif(
    (CHROMIUM is None or DRIVER is None) and not os.environ.get("INHERIT_SG_REQUIRE_BROWSER"),
    reason=MISSING,
)


def artifacts_dir() -> Path:
    out = Path(os.environ.get("INHERIT_SG_ARTIFACTS") or REPO_ROOT / "tests" / "artifacts")
    out.mkdir(parents=True, exist_ok=True)
    return out


@pytest.fixture(scope="module")
def base_url(tmp_path_factory: pytest.TempPathFactory) -> Iterator[str]:
    root = tmp_path_factory.mktemp("viewer")
    write_dataset(generate_house(3, 1, 4), root / "house", width=128, height=96, workers=2)
    build_map(root / "house", root / NAME)
    config = Config(service=ServiceConfig(read_keys=[KEY]))
    app = create_app(root / NAME, config)
    with uvicorn_on_loopback(app, start_timeout_s=WAIT_S, stop_timeout_s=10) as (url, _, _):
        yield url


@pytest.fixture(scope="module")
def browser() -> Iterator[WebDriver]:
    assert CHROMIUM is not None and DRIVER is not None, MISSING
    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for arg in (
        "--headless=new",
        "--no-sandbox",
        "--disable-gpu",
        # WebGL for the 3D view on the CPU (SwiftShader): no GPU on CI machines
        "--use-angle=swiftshader",
        "--enable-unsafe-swiftshader",
        "--disable-dev-shm-usage",
        "--window-size=1500,950",
    ):
        options.add_argument(arg)
    driver = webdriver.Chrome(service=Service(executable_path=DRIVER), options=options)
    try:
        yield driver
    finally:
        driver.quit()


def test_search_highlights_the_api_answer(browser: WebDriver, base_url: str) -> None:
    expected = httpx.post(
        f"{base_url}/v1/maps/{NAME}/query",
        json={"text": QUERY},
        headers={"Authorization": f"Bearer {KEY}"},
        timeout=WAIT_S,
    ).json()["answer"]
    assert expected is not None and expected["label"] == "sofa"

    wait = WebDriverWait(browser, WAIT_S)
    browser.get(f"{base_url}/")
    # without the key the /v1 calls answer 401 and the page says so
    wait.until(ec.text_to_be_present_in_element((By.ID, "status"), "API key"))
    browser.find_element(By.ID, "key-input").send_keys(KEY + Keys.TAB)
    wait.until(ec.presence_of_element_located((By.CSS_SELECTOR, "#markers .marker")))
    tabs = browser.find_elements(By.CSS_SELECTOR, "#floor-tabs button")
    assert [t.get_attribute("data-floor") for t in tabs] == ["floor:0"]
    assert browser.find_elements(By.CSS_SELECTOR, "#tree details[data-id='floor:0']")

    box = browser.find_element(By.ID, "query-input")
    box.send_keys(QUERY + Keys.ENTER)
    marker = wait.until(ec.presence_of_element_located((By.CSS_SELECTOR, ".marker.answer")))
    assert marker.get_attribute("data-id") == expected["id"]
    assert len(browser.find_elements(By.CSS_SELECTOR, ".marker.answer")) == 1
    assert browser.find_element(By.ID, "answer").get_attribute("data-id") == expected["id"]
    assert browser.find_elements(By.CSS_SELECTOR, "#trace li")
    # the answer's best view is shown, loaded through the keyed fetch
    wait.until(
        lambda d: d.execute_script(
            "const f = document.getElementById('view-figure');"
            "const i = document.getElementById('view-image');"
            "return !f.hidden && i.complete && i.naturalWidth > 0;"
        )
    )
    caption = browser.find_element(By.ID, "view-caption").text
    assert "best view kf:" in caption

    # a query with several candidates: the others are marked too, distinct from the answer
    many = httpx.post(
        f"{base_url}/v1/maps/{NAME}/query",
        json={"text": MANY},
        headers={"Authorization": f"Bearer {KEY}"},
        timeout=WAIT_S,
    ).json()
    others = {c["id"] for c in many["candidates"]} - {many["answer"]["id"]}
    assert others, "the second query should rank more than one candidate"
    box.clear()
    box.send_keys(MANY + Keys.ENTER)
    wait.until(
        lambda d: d.find_element(By.ID, "answer").get_attribute("data-id") == many["answer"]["id"]
    )
    answer = browser.find_element(By.CSS_SELECTOR, ".marker.answer")
    assert answer.get_attribute("data-id") == many["answer"]["id"]
    marked = browser.find_elements(By.CSS_SELECTOR, ".marker.candidate")
    assert {m.get_attribute("data-id") for m in marked} == others
    shot = artifacts_dir() / "viewer.png"
    assert browser.save_screenshot(str(shot)) and shot.stat().st_size > 10_000


def _canvas_is_drawn(png: bytes) -> tuple[float, int]:
    """Spread of the canvas screenshot's pixels and its number of distinct colours."""
    import io

    import numpy as np
    from PIL import Image

    pixels = np.asarray(Image.open(io.BytesIO(png)).convert("RGB"), dtype=np.float32)
    colours = len(np.unique(pixels.reshape(-1, 3).astype(np.uint8), axis=0))
    return float(pixels.std()), colours


def test_3d_view_draws_the_floor_and_highlights_the_answer(
    browser: WebDriver, base_url: str
) -> None:
    headers = {"Authorization": f"Bearer {KEY}"}
    scene = httpx.get(
        f"{base_url}/v1/maps/{NAME}/scene3d", params={"floor": "floor:0"}, headers=headers
    ).json()
    assert scene["objects"] and scene["rooms"] and all(r["outlines"] for r in scene["rooms"])
    expected = httpx.post(
        f"{base_url}/v1/maps/{NAME}/query", json={"text": MANY}, headers=headers, timeout=WAIT_S
    ).json()

    wait = WebDriverWait(browser, WAIT_S)
    browser.get(f"{base_url}/")
    key = browser.find_element(By.ID, "key-input")
    if not key.get_attribute("value"):
        key.send_keys(KEY + Keys.TAB)
    wait.until(ec.presence_of_element_located((By.CSS_SELECTOR, "#markers .marker")))
    browser.find_element(By.CSS_SELECTOR, "#view-switch button[data-view='3d']").click()
    info = wait.until(
        lambda d: d.execute_script(
            "const i = window.isg3d && window.isg3d.info(); return i && i.objects ? i : null;"
        )
    )
    assert info["webgl"], info["error"]
    assert info["objects"] == len(scene["objects"])
    assert info["rooms"] == len(scene["rooms"])
    assert browser.find_element(By.ID, "bev-wrap").get_attribute("hidden") is not None

    box = browser.find_element(By.ID, "query-input")
    box.clear()
    box.send_keys(MANY + Keys.ENTER)
    answer_id = expected["answer"]["id"]
    info = wait.until(
        lambda d: d.execute_script(
            "const i = window.isg3d.info(); return i.answer === arguments[0] ? i : null;",
            answer_id,
        )
    )
    others = {c["id"] for c in expected["candidates"]} - {answer_id}
    assert set(info["candidates"]) == others
    assert info["frames"] > 0 and info["drawCalls"] > 0

    canvas = browser.find_element(By.ID, "canvas3d")
    png = canvas.screenshot_as_png
    shot = artifacts_dir() / "viewer3d.png"
    shot.write_bytes(png)
    browser.save_screenshot(str(artifacts_dir() / "viewer3d-page.png"))
    spread, colours = _canvas_is_drawn(png)
    assert spread > 10 and colours > 50, (spread, colours)  # not a blank canvas
