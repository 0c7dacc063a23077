"""Process handling and log parsing shared by the soak and the end-to-end tests."""
import os
import re
import select
import subprocess
import time


class Proc:
    """A child process whose stderr (and stdout unless piped) goes to a log file."""

    def __init__(self, argv, log_path, env=None, append=False, stdout_pipe=False):
        self.log_path = log_path
        self.log = open(log_path, "a" if append else "w")
        self.start_offset = self.log.tell()
        self.popen = subprocess.Popen(
            argv, env=env, stdout=subprocess.PIPE if stdout_pipe else self.log,
            stderr=self.log, text=stdout_pipe or None)

    def alive(self):
        return self.popen.poll() is None

    def stop(self, sig, timeout=20.0):
        if self.alive():
            self.popen.send_signal(sig)
        try:
            self.popen.wait(timeout)
        except subprocess.TimeoutExpired:
            self.popen.kill()
            self.popen.wait()
        self.log.close()
        return self.popen.returncode

    def text(self):
        if not self.log.closed:
            self.log.flush()
        with open(self.log_path, errors="replace") as f:
            f.seek(self.start_offset)
            return f.read()


def wait_for_line(stream, timeout):
    """The first line of a child's piped stdout, or None after timeout seconds."""
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        ready, _, _ = select.select([stream], [], [], max(0.0, end - time.monotonic()))
        if ready:
            line = stream.readline()
            return line.strip() if line else None
    return None


def wait_for_text(path, pattern, timeout, alive=lambda: True):
    """Waits until the file at path matches the regex pattern; returns the match."""
    end = time.monotonic() + timeout
    while time.monotonic() < end and alive():
        try:
            m = re.search(pattern, open(path, errors="replace").read())
        except FileNotFoundError:
            m = None
        if m:
            return m
        time.sleep(0.05)
    return None


def rss_kib(pid):
    try:
        with open("/proc/%d/status" % pid) as f:
            for line in f:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1])
    except (FileNotFoundError, ProcessLookupError):
        pass
    return None


def commits_in(text):
    """Journal record numbers a station log reports as committed."""
    return {int(n) for n in re.findall(r"committed as journal record (\d+)", text)}


def start_checksum(text):
    """The model checksum a station log reports at start-up (after recovery)."""
    m = re.search(r"twister-station: mesh .*checksum ([0-9a-f]{16})", text)
    return m.group(1) if m else None
