#!/usr/bin/env python3
"""Drives radfarmd's status page in headless Chromium (Selenium + chromedriver) for
status_page_browser_test.cc, which runs the farm: a master with --http and a web token, and one
agent. This script opens the page, submits a job through the radfarm CLI, and asserts on the
rendered DOM: the agent is listed, the job appears, its progress moves, the page's pause and
resume buttons work once signed in with the token, and the job reaches done with a preview. It
saves a screenshot of the finished page, then signs out: no cookie was ever set, and the tab's
session is gone. Every wait polls with a generous timeout; nothing sleeps
a fixed time. Exit 0 on success; any failure raises with what the page showed."""

import argparse
import subprocess
import sys
import time

from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.by import By

TIMEOUT = 300  # seconds, for every wait: a loaded CI machine is slow, a hang still ends


def wait_for(driver, what, condition, timeout=TIMEOUT):
    """Polls condition() (truthy result returned) until the timeout, then fails naming `what`."""
    deadline = time.monotonic() + timeout
    last_error = None
    while time.monotonic() < deadline:
        try:
            value = condition()
            if value:
                return value
        except Exception as e:  # the DOM changes under us while the page redraws
            last_error = e
        time.sleep(0.05)  # polling interval, not a synchronisation
    body = driver.find_element(By.TAG_NAME, "body").text
    raise AssertionError(f"timed out waiting for {what} (last error: {last_error})\npage:\n{body}")


def job_row(driver, job_id):
    rows = driver.find_elements(By.CSS_SELECTOR, f'#jobs tbody tr[data-key="{job_id}"]')
    return rows[0] if rows else None


def job_field(driver, job_id, field):
    row = job_row(driver, job_id)
    return row.get_attribute(f"data-{field}") if row else None


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--url", required=True)
    p.add_argument("--token", required=True)
    p.add_argument("--cli", required=True)
    p.add_argument("--control", required=True)
    p.add_argument("--scene", required=True)
    p.add_argument("--agent", required=True)
    p.add_argument("--screenshot", required=True)
    args = p.parse_args()

    options = webdriver.ChromeOptions()
    options.binary_location = "/usr/bin/chromium"
    # Root in CI: Chromium's sandbox needs user namespaces it may not have there.
    for flag in ("--headless=new", "--no-sandbox", "--disable-dev-shm-usage", "--disable-gpu",
                 "--window-size=1280,900", "--force-device-scale-factor=1"):
        options.add_argument(flag)
    driver = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)
    try:
        driver.get(args.url)
        # Before its first update the page says it is loading: it asserted "No jobs yet" and "No
        # agent is connected" on a farm it had not heard from. One script, so no redraw between.
        first = driver.execute_script(
            "const shown = (id) => !document.getElementById(id).hidden;"
            "return {drawn: document.getElementById('updated').textContent !== '',"
            "        loading: shown('loading-jobs') && shown('loading-agents'),"
            "        empty: shown('no-jobs') || shown('no-agents')};")
        if not first["drawn"]:
            assert first["loading"] and not first["empty"], first
        wait_for(driver, "the event stream to connect", lambda: driver.find_element(
            By.ID, "connection").get_attribute("data-state") == "live")
        wait_for(driver, f"agent {args.agent} to be listed", lambda: driver.find_elements(
            By.CSS_SELECTOR, f'#agents tbody tr[data-name="{args.agent}"]'))
        agent = driver.find_element(By.CSS_SELECTOR, f'#agents tbody tr[data-name="{args.agent}"]')
        assert agent.get_attribute("data-state") in ("idle", "busy"), agent.text
        wait_for(driver, "the page to say there are no jobs", lambda: driver.find_element(
            By.ID, "no-jobs").is_displayed())

        submitted = subprocess.run(
            [args.cli, "--control", args.control, "submit", args.scene, "--name", "browser-test"],
            check=True, capture_output=True, text=True)
        job_id = submitted.stdout.strip()
        print(f"submitted job {job_id}")

        wait_for(driver, f"job {job_id} to appear", lambda: job_row(driver, job_id))
        assert "browser-test" in job_row(driver, job_id).text
        # Progress moves: two different values seen while the job runs, both short of done.
        first = float(wait_for(driver, "the job to run with some progress", lambda: (
            job_field(driver, job_id, "state") == "running"
            and float(job_field(driver, job_id, "progress")) > 0
            and job_field(driver, job_id, "progress"))))
        wait_for(driver, "the job's progress to move", lambda: (
            float(job_field(driver, job_id, "progress")) != first))
        print(f"progress moved from {first} to {job_field(driver, job_id, 'progress')}")

        # Sign in with the token; the page then shows pause and cancel.
        driver.find_element(By.ID, "token").send_keys(args.token)
        driver.find_element(By.CSS_SELECTOR, "#login button").click()
        wait_for(driver, "signing in", lambda: "actions enabled" in driver.find_element(
            By.ID, "session").text)
        pause = wait_for(driver, "the pause button", lambda: job_row(driver, job_id)
                         .find_elements(By.CSS_SELECTOR, 'button[data-action="pause"]'))
        pause[0].click()
        wait_for(driver, "the job to be paused", lambda: job_field(driver, job_id, "state") ==
                 "paused")
        resume = wait_for(driver, "the resume button", lambda: job_row(driver, job_id)
                          .find_elements(By.CSS_SELECTOR, 'button[data-action="resume"]'))
        resume[0].click()
        wait_for(driver, "the job to leave paused", lambda: job_field(driver, job_id, "state") in
                 ("queued", "running", "done"))

        wait_for(driver, "the job to be done", lambda: job_field(driver, job_id, "state") ==
                 "done")
        assert float(job_field(driver, job_id, "progress")) == 1.0
        assert "100.0%" in job_row(driver, job_id).text, job_row(driver, job_id).text
        # Where its time went: a line per phase, every place's CPU seconds in its title.
        timeline = wait_for(driver, "the job's timeline", lambda: driver.execute_script(
            "const c = document.querySelector(arguments[0]);"
            "return c && c.textContent.includes('display') ? [c.textContent, c.title] : null;",
            f'#jobs tbody tr[data-key="{job_id}"] td.timeline'))
        assert "gather" in timeline[0] and "agents" in timeline[1], timeline
        print(f"timeline shown: {timeline[0]!r}")
        wait_for(driver, "the preview image to load", lambda: driver.execute_script(
            "const i = document.querySelector(arguments[0]);"
            "return i !== null && i.complete && i.naturalWidth > 0;",
            f'#jobs tbody tr[data-key="{job_id}"] img.preview'))
        # The preview is big enough to see (it was 60 x 45 px) and a link to the whole image.
        size = wait_for(driver, "the preview at its size, in a link", lambda: driver.execute_script(
            "const i = document.querySelector(arguments[0]);"
            "const a = i && i.closest('a.preview-link');"
            "return a && a.href.startsWith('blob:') && Math.max(i.width, i.height) >= 150"
            "  ? [i.width, i.height] : null;",
            f'#jobs tbody tr[data-key="{job_id}"] img.preview'))
        print(f"preview shown at {size[0]} x {size[1]} px, linked")
        for text in ("paused", "done"):
            wait_for(driver, f"an event saying {text}", lambda: text in driver.find_element(
                By.ID, "events").text)
        driver.save_screenshot(args.screenshot)
        print(f"screenshot: {args.screenshot}")

        # Signing out ends the session: the tab forgets it and the page is read-only again.
        assert driver.execute_script("return sessionStorage.getItem('radfarm.session')")
        assert not driver.get_cookies(), driver.get_cookies()  # nothing for another port to take
        driver.find_element(By.ID, "logout").click()
        wait_for(driver, "signing out", lambda: "read-only until you sign in" in
                 driver.find_element(By.ID, "session").text)
        assert driver.execute_script("return sessionStorage.getItem('radfarm.session')") is None
    finally:
        driver.quit()
    return 0


if __name__ == "__main__":
    sys.exit(main())
