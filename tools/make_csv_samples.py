#!/usr/bin/env python3
"""Writes the CSV samples in data-samples/csv/ from the synthetic x-IMU recordings of data-samples/recordings/.

   tools/make_csv_samples.py [OUTDIR]        (default: data-samples/csv beside this script's checkout)

Each sample holds the gyroscope (and where the app or logger has one, the accelerometer) of one synthetic trial, in
the header, units, number format and time base of one kind of file that labs bring; the attitude is withheld, as
these files have none. The x-IMU files hold one sample per line at 256 Hz (the rate of their _Registers.csv):
sample k is at k/256 s. Deterministic: the same inputs give the same bytes.

  phyphox/Gyroscope.csv       phyphox's CSV export of the "Gyroscope" experiment: quoted header
                              "Time (s)","Gyroscope x (rad/s)","Gyroscope y (rad/s)","Gyroscope z (rad/s)",
                              "Absolute (rad/s)", numbers as 1.234567890E-1
  sensor-logger/Gyroscope.csv Sensor Logger's Gyroscope.csv: time (ns since 1970), seconds_elapsed, z, y, x (rad/s)
  sensor-logger/TotalAcceleration.csv
                              its accelerometer with gravity (Android), in a file of its own with its own times: the
                              same header, m/s² (9.81 per g, the synthetic model's gravity), sampled half a gyro step
                              after each gyro sample (the mean of the two x-IMU samples around it), one row fewer
  arduino/log.csv             a microcontroller logger: micros() (a 32-bit counter that wraps during the trial),
                              gx [dps] … and ax [g] …, with a quoted free-text column
  quoted/trial.csv            a spreadsheet's export: every field quoted, ';' between fields, decimal commas
"""
import math
import os
import sys

HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RATE_HZ = 256
# (sample, source trial); one trial per kind of file, from different blocks and positions.
SAMPLES = {
    "phyphox": "block2-A-1",
    "sensor-logger": "block1-A-1",
    "arduino": "block3-A-1",
    "quoted": "block1-B-1",
}
EPOCH_START_NS = 1_700_000_000_000_000_000  # 2023-11-14 22:13:20 UTC
STEP_NS = 1_000_000_000 // RATE_HZ  # 3906250 ns, exact at 256 Hz
G_M_S2 = 9.81  # m/s² per g: the synthetic model's gravity (io/README.md, "Columns")
MICROS_START = 2**32 - 2_500_000  # the counter wraps 2.5 s into the trial


def read_ximu(prefix):
    rows = []
    with open(prefix + "_CalInertialAndMag.csv", encoding="ascii") as f:
        header = f.readline().strip().split(",")
        gx = header.index("Gyroscope X (deg/s)")
        ax = header.index("Accelerometer X (g)")
        for line in f:
            cells = line.strip().split(",")
            if len(cells) < len(header):
                continue
            gyro = [float(c) for c in cells[gx:gx + 3]]
            accel = [float(c) for c in cells[ax:ax + 3]]
            rows.append((gyro, accel))
    return rows


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", encoding="utf-8", newline="") as f:
        f.write(text)


def phyphox(rows):
    lines = ['"Time (s)","Gyroscope x (rad/s)","Gyroscope y (rad/s)","Gyroscope z (rad/s)","Absolute (rad/s)"']
    for k, (g, _) in enumerate(rows):
        w = [math.radians(v) for v in g]
        values = [k / RATE_HZ] + w + [math.sqrt(sum(v * v for v in w))]
        lines.append(",".join("%.9E" % v for v in values))
    return "\n".join(lines) + "\n"


def sensor_logger(rows):
    lines = ["time,seconds_elapsed,z,y,x"]
    for k, (g, _) in enumerate(rows):
        w = [math.radians(v) for v in g]
        t_ns = EPOCH_START_NS + k * STEP_NS
        lines.append("%d,%s,%r,%r,%r" % (t_ns, repr(k / RATE_HZ), w[2], w[1], w[0]))
    return "\n".join(lines) + "\n"


def sensor_logger_accel(rows):
    lines = ["time,seconds_elapsed,z,y,x"]
    for k in range(len(rows) - 1):
        a = [0.5 * (rows[k][1][i] + rows[k + 1][1][i]) * G_M_S2 for i in range(3)]
        t_ns = EPOCH_START_NS + k * STEP_NS + STEP_NS // 2
        lines.append("%d,%s,%r,%r,%r" % (t_ns, repr((k + 0.5) / RATE_HZ), a[2], a[1], a[0]))
    return "\n".join(lines) + "\n"


def arduino(rows):
    lines = ['micros,gx [dps],gy [dps],gz [dps],ax [g],ay [g],az [g],note']
    for k, (g, a) in enumerate(rows):
        micros = (MICROS_START + (k * 1_000_000) // RATE_HZ) % 2**32
        note = '"released, by hand"' if k == 0 else '""'
        lines.append("%d,%s,%s,%s,%s,%s,%s,%s" % ((micros,) + tuple("%.4f" % v for v in g) +
                                                 tuple("%.6f" % v for v in a) + (note,)))
    return "\r\n".join(lines) + "\r\n"


def quoted(rows):
    header = ["Time (s)", "Gyroscope X (deg/s)", "Gyroscope Y (deg/s)", "Gyroscope Z (deg/s)",
              "Accelerometer X (g)", "Accelerometer Y (g)", "Accelerometer Z (g)", 'Comment; "as typed"']
    lines = [";".join('"' + h.replace('"', '""') + '"' for h in header)]
    for k, (g, a) in enumerate(rows):
        values = ["%.6f" % (k / RATE_HZ)] + ["%.4f" % v for v in g] + ["%.6f" % v for v in a]
        cells = ['"' + v.replace(".", ",") + '"' for v in values] + ['"' + ("start; ok" if k == 0 else "") + '"']
        lines.append(";".join(cells))
    return "\n".join(lines) + "\n"


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "data-samples", "csv")
    writers = {"phyphox": ("phyphox/Gyroscope.csv", phyphox),
               "sensor-logger": ("sensor-logger/Gyroscope.csv", sensor_logger),
               "arduino": ("arduino/log.csv", arduino),
               "quoted": ("quoted/trial.csv", quoted)}
    for name, trial in SAMPLES.items():
        rows = read_ximu(os.path.join(HERE, "data-samples", "recordings", trial))
        path, writer = writers[name]
        write(os.path.join(out, path), writer(rows))
        if name == "sensor-logger":
            write(os.path.join(out, "sensor-logger", "TotalAcceleration.csv"), sensor_logger_accel(rows))


if __name__ == "__main__":
    main()
