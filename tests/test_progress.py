"""Progress lines of long steps (stderr, only when slow) and bars without an early estimate."""

from __future__ import annotations

import io
import time

from anvilwave.output.progress import NO_ESTIMATE, Step, bar


def test_a_step_speaks_only_when_slow():
    stream = io.StringIO()
    with Step("quick...", after=0.5, stream=stream) as quick:
        pass
    with Step("slow...", after=0.05, stream=stream) as slow:
        time.sleep(0.3)
    with Step("quiet...", after=0.0, enabled=False, stream=stream):
        pass
    assert not quick.printed and slow.printed
    assert stream.getvalue() == "slow...\n"


def test_the_bar_shows_no_estimate_until_warm():
    out = io.StringIO()
    b = bar(10, warm=2, file=out, desc="depths", mininterval=0)
    assert b.bar_format == NO_ESTIMATE
    b.update(1)
    assert b.bar_format == NO_ESTIMATE
    b.update(1)
    assert b.bar_format is None  # tqdm's own format, with the remaining time
    b.close()
    assert "estimating" in out.getvalue()
    assert bar(3, enabled=False) is None
