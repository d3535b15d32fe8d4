#!/usr/bin/env python3
"""The course's CGR test scenes rendered by this program beside three students' renders of them.

    cargo build --release && python3 benches/cgr_students.py sheet.png

Needs Pillow and ../shared/coursework/corpus. Prints the mean absolute difference (8-bit, all
channels) between our render and each student's, and writes a contact sheet: one row per scene,
the students' renders then ours. tests/cgr_conventions.rs asserts them against the course picture's.
"""
import json, subprocess, sys, tempfile
from pathlib import Path
from PIL import Image, ImageDraw, ImageChops, ImageStat

ROOT = Path(__file__).resolve().parent.parent
CORPUS = ROOT.parent / "shared/coursework/corpus"
STUDENTS = ["Trenza1ore__std-raytracer", "chxag__CGR-Raytracing-CW2",
            "HlnnnWnng__High-Performance-Raytracer-Image-Render"]
SCENES = [("phong_scene", "scene.json", "phong"), ("mirror_image", "mirror_image.json", None),
          ("simple_phong", "simple_phong.json", None)]
TILE = (300, 200)


def main(out):
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, file, mode in SCENES:
            scene = json.loads((CORPUS / f"chxag__CGR-Raytracing-CW2__TestSuite__{file}").read_text())
            if mode:
                scene["rendermode"] = mode
            path = Path(tmp) / f"{name}.json"
            path.write_text(json.dumps(scene))
            ours_path = Path(tmp) / f"{name}.png"
            subprocess.run([ROOT / "target/release/raytracer", path, ours_path], check=True,
                           capture_output=True)
            ours = Image.open(ours_path).convert("RGB")
            tiles = []
            for s in STUDENTS:
                p = CORPUS / f"reference/student_renders/{s}__TestSuite__{name}.png"
                who = s.split("__")[0]
                if p.is_file():
                    im = Image.open(p).convert("RGB")
                    d = sum(ImageStat.Stat(ImageChops.difference(im, ours)).mean) / 3
                    print(f"{name:14} {who:11} {d:5.1f}")
                    tiles.append((who, im))
                else:
                    tiles.append((who + " (none)", Image.new("RGB", ours.size)))
            tiles.append(("raytracer", ours))
            row = Image.new("RGB", (TILE[0] * len(tiles), TILE[1]))
            for i, (label, im) in enumerate(tiles):
                t = im.resize(TILE, Image.LANCZOS)
                ImageDraw.Draw(t).text((5, 4), f"{label}: {name}", fill=(255, 255, 0))
                row.paste(t, (TILE[0] * i, 0))
            rows.append(row)
    sheet = Image.new("RGB", (rows[0].width, TILE[1] * len(rows)))
    for i, r in enumerate(rows):
        sheet.paste(r, (0, TILE[1] * i))
    sheet.save(out, optimize=True)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "cgr-test-scenes.png")
