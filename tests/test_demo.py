"""The README's first command: the demo runs case H and writes a PNG."""

from beltrs.__main__ import main


def test_demo_writes_plot(tmp_path, capsys):
    out = tmp_path / "h.png"
    assert main(["demo", "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "tension at lower tangent points" in text and "takeup position" in text and "wall" in text
    assert out.stat().st_size > 10_000
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
