#!/usr/bin/env python3
"""Writes the seed corpora of the fuzz targets into tests/fuzz/corpus/<target>/ (tests/fuzz/README.md).

    tests/fuzz/make_corpus.py build/tools/rockfit

Seeds come from data-samples/ (cut to their first rows: short inputs fuzz faster), from files the
rockfit binary writes (short synthetic recordings, HDF5 stores) and from small crafted files for the
formats data-samples/ does not hold (x-IMU3, generic CSV). Deterministic: fixed seeds, no clock.
"""
import math
import pathlib
import shutil
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[2]
CORPUS = ROOT / "tests" / "fuzz" / "corpus"
SAMPLES = ROOT / "data-samples" / "recordings"
MARKER = "\n@@@ "
ROWS = 40  # data rows kept per file


def head(path, rows=ROWS):
    lines = path.read_text().splitlines(keepends=True)
    return "".join(lines[: rows + 1])


def put(target, name, text):
    folder = CORPUS / target
    folder.mkdir(parents=True, exist_ok=True)
    data = text.encode() if isinstance(text, str) else text
    (folder / name).write_bytes(data)


def gui_set(prefix, parts, rows=ROWS):
    text = head(pathlib.Path(f"{prefix}_CalInertialAndMag.csv"), rows)
    for part in parts:
        path = pathlib.Path(f"{prefix}_{part}.csv")
        if path.exists():
            text += MARKER + part + "\n" + head(path, rows if part != "Registers" else 10**6)
    return text


def ximu_gui(rockfit, tmp):
    for trial in ("block1-A-1", "block3-B-2"):
        put("ximu_gui", trial, gui_set(SAMPLES / trial, ["Registers", "DateTime", "EulerAngles", "Quaternion"]))
    put("ximu_gui", "no-registers", gui_set(SAMPLES / "block2-A-1", ["EulerAngles"]))
    put("ximu_gui", "quaternion-only", gui_set(SAMPLES / "block2-B-1", ["Registers", "Quaternion"]))
    synth = [rockfit, "synth", "--b1", "0.05", "--b2", "0.03", "--h", "0.2", "--density", "2692", "--alpha", "0.15",
             "--t0", "0.05", "--duration", "0.25", "--seed", "3"]
    subprocess.run(synth + ["--rate", "128", "--quaternion-rate", "64", "-o", str(tmp / "m")], check=True,
                   stdout=subprocess.DEVNULL)
    put("ximu_gui", "matrix-half-rate", gui_set(tmp / "m", ["Registers", "DateTime", "RotationMatrix"]))
    subprocess.run(synth + ["--crlf", "-o", str(tmp / "c")], check=True, stdout=subprocess.DEVNULL)
    put("ximu_gui", "crlf", gui_set(tmp / "c", ["Registers", "EulerAngles"], 16))


def ximu3_rows(n, step_us, columns, start_us=19150794, skip=()):
    """Rows of a slowly rocking sensor: column k of row i is a smooth function, printed as the logger does."""
    lines = []
    t = start_us
    for i in range(n):
        if i in skip:
            t += step_us
        values = columns(i)
        lines.append(f"{t}," + ",".join(f"{v:.6f}" for v in values))
        t += step_us
    return "\n".join(lines) + "\n"


def ximu3(_rockfit, _tmp):
    inertial = ("Timestamp (us),Gyroscope X (deg/s),Gyroscope Y (deg/s),Gyroscope Z (deg/s),Accelerometer X (g),"
                "Accelerometer Y (g),Accelerometer Z (g)\n")
    gyro = lambda i: (0.2 * math.sin(i / 5), 30 * math.cos(i / 7), -0.1, 0.01, 0.2 * math.sin(i / 7), 0.98)
    half = lambda i: 0.5 * 0.2 * math.sin(i / 7)
    quat = lambda i: (math.cos(half(i)), 0.0, math.sin(half(i)), 0.0)
    euler = lambda i: (0.0, math.degrees(0.2 * math.sin(i / 7)), 0.0)

    def matrix(i):
        a = 0.2 * math.sin(i / 7)
        return (math.cos(a), 0, math.sin(a), 0, 1, 0, -math.sin(a), 0, math.cos(a))

    acc = lambda i: quat(i) + (0.001, -0.002, 0.003)
    main = inertial + ximu3_rows(ROWS, 20000, gyro)
    put("ximu3", "inertial-only", main)
    put("ximu3", "quaternion", main + MARKER + "Quaternion\nTimestamp (us),W,X,Y,Z\n" + ximu3_rows(ROWS, 20000, quat))
    put("ximu3", "euler-and-matrix",
        main + MARKER + "EulerAngles\nTimestamp (us),Roll (deg),Pitch (deg),Yaw (deg)\n" +
        ximu3_rows(ROWS // 2, 20000, euler) + MARKER + "RotationMatrix\nTimestamp (us),XX,XY,XZ,YX,YY,YZ,ZX,ZY,ZZ\n" +
        ximu3_rows(ROWS // 2, 20000, matrix, start_us=19150794 + 20000 * (ROWS // 2)))
    header = "Timestamp (us),Quaternion W,Quaternion X,Quaternion Y,Quaternion Z,Acceleration X (g),Acceleration Y (g),Acceleration Z (g)\n"
    put("ximu3", "linear-and-earth",
        main + MARKER + "LinearAcceleration\n" + header + ximu3_rows(ROWS // 2, 20000, acc) + MARKER +
        "EarthAcceleration\n" + header + ximu3_rows(ROWS // 2, 20000, acc, start_us=19150794 + 20000 * (ROWS // 2)))
    put("ximu3", "dropped-messages", inertial + ximu3_rows(ROWS, 20000, gyro, skip=(7, 8, 20)))


def generic_csv(_rockfit, _tmp):
    full = "time=Time (s)@s;gyro=Gx,Gy,Gz@deg/s;euler=Roll,Pitch,Yaw@deg;accel=Ax,Ay,Az@g\n"
    rows = "".join(f"{i / 100:.2f},{math.sin(i / 5):.4f},{20 * math.cos(i / 7):.4f},0.1,0,{5 * math.sin(i / 7):.3f},0,"
                   f"0.01,0.02,0.99\n" for i in range(ROWS))
    put("generic_csv", "full-map", full + "Time (s),Gx,Gy,Gz,Roll,Pitch,Yaw,Ax,Ay,Az\n" + rows)
    put("generic_csv", "ms-radians",
        "time=t@ms;gyro=wx,wy,wz@rad/s\nt,wx,wy,wz\n" +
        "".join(f"{10 * i},{0.01 * i:.3f},{math.sin(i / 9):.5f},-0.002\n" for i in range(ROWS)))
    put("generic_csv", "no-time-rate",
        "!gyro=Gyroscope X (deg/s),Gyroscope Y (deg/s),Gyroscope Z (deg/s)\n" +
        head(SAMPLES / "block1-A-1_CalInertialAndMag.csv"))
    put("generic_csv", "detected-xio-headers", "!\n" + head(SAMPLES / "block2-A-1_CalInertialAndMag.csv"))
    put("generic_csv", "semicolons",
        "time=time@s;gyro=gx,gy,gz@deg/s;accel=ax,ay,az@m/s^2\ntime;gx;gy;gz;ax;ay;az\n" +
        "".join(f"{i / 256:.6f};0,5;-{i % 7},25;0;0;0;9,81\n".replace(".", ",") for i in range(ROWS)))


def option_grammars(_rockfit, _tmp):
    for k, text in enumerate([
            "identity", "x,-y,-z", "-y,x,z", "z,x,y", "0.7071068,0,0.7071068,0", "1,0,0,0", "0.5,0.5,0.5,0.5",
            "time=Time (s)@s;gyro=Gx,Gy,Gz@deg/s;euler=Roll,Pitch,Yaw@deg;accel=Ax,Ay,Az@g",
            "gyro=Gyroscope X (deg/s),Gyroscope Y (deg/s),Gyroscope Z (deg/s)",
            "time=t@us;gyro=a,b,c@rad/s;accel=d,e,f@m/s^2", "time=Timestamp (us);gyro=x,y,z@deg/s;euler=r,p,y@rad"]):
        put("option_grammars", f"seed-{k:02d}", text)


def manifest(_rockfit, _tmp):
    put("manifest", "data-samples", (ROOT / "data-samples" / "manifest.toml").read_text())
    put("manifest", "every-key", '''[[blocks]]
id = "B3"
b1 = 0.05
b2 = 0.03
h = 0.20
mass = 1.5
notes = "granite"

[[trials]]
id = "B3-A-1"
block = "B3"
position = "A"
files = "raw/B3-A-1"
format = "ximu-gui"
rate = 256
mounting = "x,-y,-z"
notes = "first"

[[trials]]
id = "B3-B-1"
block = "B3"
position = "B"
files = "x3/"
format = "ximu3"
mounting = "0.7071068,0,0.7071068,0"

[[trials]]
id = "B3-C-1"
block = "B3"
position = "C"
files = "c.csv"
format = "csv"
rate = 100.5
''')
    put("manifest", "inline-tables", 'blocks = [{id = "a", b1 = 1e-2, b2 = 2e-2, h = 0.1, density = 2.6e3}]\n'
        'trials = [{id = "t", block = "a", position = "A", files = "f"}]\n')


def rockfit_hdf5(rockfit, tmp):
    synth = [rockfit, "synth", "--b1", "0.05", "--b2", "0.03", "--h", "0.2", "--density", "2692", "--alpha", "0.15",
             "--t0", "0.05", "--duration", "0.4", "--rate", "64", "--seed", "5", "--no-rotation-matrix"]
    subprocess.run(synth + ["-o", str(tmp / "s")], check=True, stdout=subprocess.DEVNULL)
    subprocess.run([rockfit, "correct", str(tmp / "s"), "-o", str(tmp / "corrected.h5")], check=True,
                   stdout=subprocess.DEVNULL)
    put("rockfit_hdf5", "correct", (tmp / "corrected.h5").read_bytes())
    subprocess.run([rockfit, "simulate", "--b1", "0.05", "--b2", "0.03", "--h", "0.2", "--density", "2692", "--alpha",
                    "0.1", "--lambda", "0.9", "--rate", "32", "--t-max", "0.5", "--format", "hdf5", "-o",
                    str(tmp / "trajectory.h5")], check=True, stdout=subprocess.DEVNULL)
    put("rockfit_hdf5", "simulate", (tmp / "trajectory.h5").read_bytes())
    (tmp / "m.toml").write_text('[[blocks]]\nid = "b"\nb1 = 0.05\nb2 = 0.03\nh = 0.2\ndensity = 2692\n\n'
                                '[[trials]]\nid = "t1"\nblock = "b"\nposition = "A"\nfiles = "s"\n')
    subprocess.run([rockfit, "summary", str(tmp / "m.toml"), "-o", str(tmp / "summary.h5")], check=True,
                   stdout=subprocess.DEVNULL)
    put("rockfit_hdf5", "summary", (tmp / "summary.h5").read_bytes())


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: tests/fuzz/make_corpus.py ROCKFIT_BINARY")
    rockfit = str(pathlib.Path(sys.argv[1]).resolve())
    shutil.rmtree(CORPUS, ignore_errors=True)
    with tempfile.TemporaryDirectory() as tmp:
        for make in (ximu_gui, ximu3, generic_csv, option_grammars, manifest, rockfit_hdf5):
            make(rockfit, pathlib.Path(tmp))
    for folder in sorted(CORPUS.iterdir()):
        files = list(folder.iterdir())
        print(f"{folder.name:16s} {len(files):3d} seeds, {sum(f.stat().st_size for f in files):8d} bytes")


if __name__ == "__main__":
    main()
