"""ccal.history and ccal.history_add against the command-line program (`ccal history`): statements recorded
from Python, read back with E_n, the drift and a prediction; the JSON the same as the program's; a missing store
and a bad keyword refused; a record superseded, a history exported and imported (history_supersede,
history_export, history_import) as `ccal history supersede`, `export` and `import` do. Run by ctest with Debian's python3, the module on PYTHONPATH and the program in
CCAL_PROGRAM."""

import json
import math
import os
import subprocess
import tempfile
import unittest

import ccal


def statement(k2, u):
    return json.dumps({"coverage_probability": 0.95, "coefficients": {
        "K2": {"unit": "deg/s/g^2", "corrected_estimate": k2, "expanded_uncertainty": u, "coverage_factor": 2.0,
               "effective_dof": None}}})


class HistoryTest(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.TemporaryDirectory()
        self.db = os.path.join(self.folder.name, "h.sqlite")
        # Years 0, 1, 3 (by the dates, one year apart then two) with u = 0.1, 0.1, 0.2.
        for i, (k2, u, date) in enumerate([(5.0, 0.2, "2020-06-01"), (5.25, 0.2, "2021-06-01"),
                                           (5.75, 0.4, "2023-06-01")]):
            path = os.path.join(self.folder.name, f"s{i}.json")
            with open(path, "w", encoding="utf-8") as f:
                f.write(statement(k2, u))
            self.assertEqual(ccal.history_add(path, db=self.db, serial="SN 1", date=date), i + 1)

    def tearDown(self):
        self.folder.cleanup()

    def test_the_history_read_back(self):
        h = ccal.history("SN 1", db=self.db, at="2024-06-01")
        self.assertEqual([r.date for r in h.records], ["2020-06-01", "2021-06-01", "2023-06-01"])
        k2 = h.coefficients[0]
        # SI (the one unit rule): × display_scale (180/π) the statements' deg/s/g^2, to 1e-15 relative (a division
        # and a multiplication by the scale).
        self.assertEqual((k2.unit, k2.display_scale), ("deg/s/g^2", 180 / math.pi))
        for value, recorded in zip(k2.values, [5.0, 5.25, 5.75]):
            self.assertAlmostEqual(value * k2.display_scale, recorded, delta=1e-15 * recorded)
        self.assertAlmostEqual(k2.drift.slope * k2.display_scale, json.loads(h.to_json())["coefficients"]["K2"]
                               ["drift"]["slope_per_year"], delta=1e-14)
        # E_n by hand: 0.25/√(0.2² + 0.2²) and 0.5/√(0.2² + 0.4²).
        self.assertAlmostEqual(k2.normalised_errors[0].value, 0.25 / math.sqrt(0.08), places=14)
        self.assertAlmostEqual(k2.normalised_errors[1].value, 0.5 / math.sqrt(0.2), places=14)
        self.assertTrue(k2.drift.available)
        self.assertGreater(k2.drift.slope, 0)
        self.assertIsNotNone(k2.prediction)
        rows = h.display().rows
        self.assertEqual(len(rows), 3)
        self.assertEqual((rows[1]["coefficient"], rows[1]["date"]), ("K2", "2021-06-01"))
        self.assertAlmostEqual(rows[1]["E_n"], 0.25 / math.sqrt(0.08), places=14)
        self.assertIsNone(rows[0]["E_n"])

    def test_the_serial_numbers_listed(self):
        # The store of setUp: SN 1 with its three calibrations, none superseded, the last of 2023-06-01.
        (serial,) = ccal.history_list(db=self.db)
        self.assertEqual((serial.serial, serial.calibrations, serial.superseded, serial.last_date),
                         ("SN 1", 3, 0, "2023-06-01"))
        with self.assertRaises(TypeError):
            ccal.history_list(db=self.db, serial="SN 1")

    def test_the_same_json_as_the_program(self):
        program = os.environ.get("CCAL_PROGRAM")
        if not program:
            self.skipTest("CCAL_PROGRAM is not set")
        out = subprocess.run([program, "history", "show", "SN 1", "--db", self.db, "--format", "json"], check=True,
                             capture_output=True, text=True).stdout
        self.assertEqual(json.loads(out), json.loads(ccal.history("SN 1", db=self.db).to_json()))

    def test_refusals(self):
        with self.assertRaisesRegex(ccal.InputError, "no history store there"):
            ccal.history("SN 1", db=os.path.join(self.folder.name, "none.sqlite"))
        with self.assertRaisesRegex(ccal.InputError, "no calibration of 'SN 2'"):
            ccal.history("SN 2", db=self.db)
        with self.assertRaises(TypeError):
            ccal.history("SN 1", db=self.db, unknown=1)

    def test_what_the_history_could_not_use_is_refused_and_leaves_no_store(self):
        new = os.path.join(self.folder.name, "new.sqlite")
        bad = os.path.join(self.folder.name, "bad.json")
        with open(bad, "w", encoding="utf-8") as f:
            f.write(statement(0.02, -1.0))
        with self.assertRaisesRegex(ccal.InputError, "finite U ≥ 0"):
            ccal.history_add(bad, db=new, serial="SN 1", date="2024-01-01")
        self.assertFalse(os.path.exists(new))
        # A certificate replacing one the new store does not hold: refused once the store is open, no file left.
        with open(bad, "w", encoding="utf-8") as f:
            f.write(json.dumps(dict(json.loads(statement(0.02, 0.2)), certificate={"replaces": "C-0"})))
        with self.assertRaisesRegex(ccal.InputError, "replaces certificate 'C-0'"):
            ccal.history_add(bad, db=new, serial="SN 1", date="2024-01-01")
        self.assertFalse(os.path.exists(new))
        self.assertEqual(os.listdir(self.folder.name).count("new.sqlite"), 0)

    def test_a_record_superseded(self):
        # Record 2 superseded by record 3: left out of E_n and the drift, kept in the records with its reason.
        self.assertIsNone(ccal.history_supersede(2, db=self.db, by=3, reason="mounting screw loose"))
        h = ccal.history("SN 1", db=self.db)
        self.assertEqual([(r.id, r.superseded_by, r.superseded_reason) for r in h.records],
                         [(1, None, ""), (2, 3, "mounting screw loose"), (3, None, "")])
        self.assertEqual(h.coefficients[0].ids, [1, 3])
        self.assertEqual(ccal.history_list(db=self.db)[0].superseded, 1)
        # The library's refusals, as the program words them but for the option's name.
        with self.assertRaisesRegex(ccal.InputError, "calibration 2 is already superseded"):
            ccal.history_supersede(2, db=self.db, reason="again")
        with self.assertRaisesRegex(ccal.InputError, "^reason: is needed to supersede calibration 1"):
            ccal.history_supersede(1, db=self.db)
        with self.assertRaisesRegex(ccal.InputError, "no calibration 7 in the history store"):
            ccal.history_supersede(7, db=self.db, reason="typo")
        with self.assertRaisesRegex(ccal.InputError, "^by: -1 "):
            ccal.history_supersede(1, db=self.db, by=-1, reason="x")
        with self.assertRaises(TypeError):
            ccal.history_supersede("1", db=self.db, reason="x")
        with self.assertRaisesRegex(TypeError, "raeson.*reason"):
            ccal.history_supersede(1, db=self.db, raeson="x")
        self.assertEqual(ccal.history_list(db=self.db)[0].superseded, 1)

    def test_a_history_exported_and_imported(self):
        ccal.history_supersede(1, db=self.db, by=2, reason="repeated")
        text = ccal.history_export("SN 1", db=self.db)
        exported = json.loads(text)
        self.assertEqual(exported["serial"], "SN 1")
        program = os.environ.get("CCAL_PROGRAM")
        if program:  # the program's export, byte for byte
            out = subprocess.run([program, "history", "export", "SN 1", "--db", self.db], check=True,
                                 capture_output=True, text=True).stdout
            self.assertEqual(out, text)
        path = os.path.join(self.folder.name, "sn1.json")
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)
        other = os.path.join(self.folder.name, "other.sqlite")
        r = ccal.history_import(path, db=other)
        self.assertEqual((r.serial, r.added, r.present, r.superseded), ("SN 1", 3, 0, 1))
        self.assertIn("added=3", repr(r))
        h, g = ccal.history("SN 1", db=other), ccal.history("SN 1", db=self.db)
        self.assertEqual([(x.date, x.superseded_by) for x in h.records],
                         [(x.date, x.superseded_by) for x in g.records])
        self.assertEqual(h.coefficients[0].values, g.coefficients[0].values)
        # Imported again: nothing added, all present.
        r = ccal.history_import(path, db=other)
        self.assertEqual((r.added, r.present, r.superseded), (0, 3, 0))
        # Refusals: a serial the store does not hold; a file that is no export, into a new store: no file left.
        with self.assertRaisesRegex(ccal.InputError, "no calibration of 'SN 2'"):
            ccal.history_export("SN 2", db=self.db)
        new = os.path.join(self.folder.name, "new.sqlite")
        with self.assertRaisesRegex(ccal.InputError, "s0.json: not an exported calibration history"):
            ccal.history_import(os.path.join(self.folder.name, "s0.json"), db=new)
        self.assertFalse(os.path.exists(new))
        with self.assertRaisesRegex(ccal.InputError, "it is a folder"):
            ccal.history_import(self.folder.name, db=new)
        self.assertFalse(os.path.exists(new))
        with self.assertRaises(TypeError):
            ccal.history_import(path, db=other, serial="SN 1")


if __name__ == "__main__":
    unittest.main()
