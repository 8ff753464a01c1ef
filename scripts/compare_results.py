#!/usr/bin/env python3
"""Whether a change left a run's results alone: a run (or one of its files) against a recorded one.

    scripts/compare_results.py REFERENCE NEW

REFERENCE and NEW are two run folders (a coupled run's, with tyre/, terrain/
and coupler/ inside, or one program's), or two files. For folders, every CSV
series and summary.json that REFERENCE holds is compared with NEW's file of
the same path; for files, the two files.

- A CSV series must be the same text in every column the reference has: the
  first differing row is printed with its line number, both rows and the
  columns in which they differ. Columns the new series adds (a new output) are
  listed and not compared; a reference column the new series lacks is a
  difference.
- A summary.json is compared value by value (numbers to the last bit, as
  nlohmann::json writes them with round-trip precision), leaving out what
  measures the machine instead of the model: wall times, speeds, the revision,
  the output folder, thread counts. The first differing key path is printed.
  Keys only in the new summary (a new output) are listed and not compared; a
  key only in the reference is a difference.

Exits 0 if everything compared is identical, 1 at the first difference, 2 on
bad arguments or a file missing from NEW. Standard library only.
"""
import json
import os
import sys

# Series that hold wall-clock times, and summary keys that measure the run's
# speed, its machine or its place on disk rather than its results.
SKIPPED_SERIES = {"pace.csv"}
SKIPPED_KEYS = {
    "performance", "wall_s", "wall_time_s", "wall_this_attempt_s", "revision", "source_revision",
    "out_dir", "threads", "omp_threads", "started_at", "finished_at", "date", "host", "run_id",
    "scene_file", "overrides", "dds", "plots", "exchange_wait_s", "compute_s", "ended_after_s",
    "dds_domain", "rejected_samples",  # where the run talked, and other runs' samples it dropped there
    "participants",  # the launcher's process table: its wall times; each process's summary is compared itself
}


def split_row(line):
    return line.rstrip("\n").split(",")


def compare_csv(ref_path, new_path):
    with open(ref_path) as ref, open(new_path) as new:
        ref_header, new_header = ref.readline(), new.readline()
        if ref_header == new_header:
            # Same columns: the rows as text.
            keep = None
            header = split_row(ref_header)
        else:
            # The new series adds columns: the reference's columns, by name, must hold the same text.
            ref_columns, new_columns = split_row(ref_header), split_row(new_header)
            missing = [c for c in ref_columns if c not in new_columns]
            if missing or len(set(ref_columns)) != len(ref_columns):
                print(f"{new_path}:1: lacks the reference's column(s) {', '.join(missing) or '(repeated names)'}")
                return False
            keep = [new_columns.index(c) for c in ref_columns]
            header = ref_columns
            added = [c for c in new_columns if c not in ref_columns]
            print(f"{new_path}: {len(added)} new column(s) not compared: {', '.join(added)}")
        number = 1
        for number, (a, b) in enumerate(zip(ref, new), start=2):
            ra, rb = split_row(a), split_row(b)
            if keep is not None:
                rb = [rb[k] if k < len(rb) else "" for k in keep]
            if ra != rb:
                columns = [header[k] if k < len(header) else str(k)
                           for k in range(max(len(ra), len(rb)))
                           if k >= len(ra) or k >= len(rb) or ra[k] != rb[k]]
                print(f"{new_path}:{number}: differs from {ref_path}:{number} in {', '.join(columns)}")
                print(f"  reference: {','.join(ra)}")
                print(f"  new:       {','.join(rb)}")
                return False
        rest_ref, rest_new = ref.read(), new.read()
    if rest_ref or rest_new:
        longer = ref_path if rest_ref else new_path
        print(f"{longer}: has rows after line {number} that the other file does not")
        return False
    return True


def first_json_difference(a, b, path, added):
    """The first difference of b from a, or None; keys only in b go to `added`."""
    if isinstance(a, dict) and isinstance(b, dict):
        for key in sorted(set(a) | set(b)):
            if key in SKIPPED_KEYS:
                continue
            if key not in a:
                added.append(f"{path}/{key}")
                continue
            if key not in b:
                return f"{path}/{key}: only in the reference"
            found = first_json_difference(a[key], b[key], f"{path}/{key}", added)
            if found:
                return found
        return None
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return f"{path}: {len(a)} items in the reference, {len(b)} in the new run"
        for k, (x, y) in enumerate(zip(a, b)):
            found = first_json_difference(x, y, f"{path}[{k}]", added)
            if found:
                return found
        return None
    if a != b or type(a) is not type(b):
        return f"{path}: reference {a!r}, new {b!r}"
    return None


def compare_json(ref_path, new_path):
    with open(ref_path) as f:
        ref = json.load(f)
    with open(new_path) as f:
        new = json.load(f)
    added = []
    found = first_json_difference(ref, new, "", added)
    if added:
        print(f"{new_path}: {len(added)} new key(s) not compared: {', '.join(added)}")
    if found:
        print(f"{new_path}: {found}")
        return False
    return True


def compare_file(ref_path, new_path):
    if not os.path.isfile(new_path):
        print(f"{new_path}: missing (the reference has {ref_path})")
        sys.exit(2)
    return compare_json(ref_path, new_path) if ref_path.endswith(".json") else compare_csv(ref_path, new_path)


def compared_files(folder):
    for root, _, files in os.walk(folder):
        for name in sorted(files):
            if name in SKIPPED_SERIES:
                continue
            if name.endswith(".csv") or name == "summary.json":
                yield os.path.relpath(os.path.join(root, name), folder)


def main():
    if len(sys.argv) != 3:
        print(__doc__.strip().splitlines()[2].strip(), file=sys.stderr)
        sys.exit(2)
    ref, new = sys.argv[1], sys.argv[2]
    if os.path.isfile(ref):
        same = compare_file(ref, new)
        count = 1
    elif os.path.isdir(ref):
        count, same = 0, True
        for rel in sorted(compared_files(ref)):
            count += 1
            if not compare_file(os.path.join(ref, rel), os.path.join(new, rel)):
                same = False
                break
    else:
        print(f"{ref}: no such file or folder", file=sys.stderr)
        sys.exit(2)
    print(f"{'identical' if same else 'DIFFERENT'}: {count} file(s) compared, {new} against {ref}")
    sys.exit(0 if same else 1)


if __name__ == "__main__":
    main()
