"""What the class and each student read: the table of the lab's questions after a test run
(scripts/lab-report, ./test.sh), and scripts/grade's results.json, junit.xml, grades.csv and
report.html."""
import csv
import html
import json
import re
import subprocess
import time
import urllib.parse
import xml.etree.ElementTree as ElementTree
from collections import Counter

from .messages import _, current_language as language, pgettext


# ------------------------------------------------------------------------------------------
# The table of the questions after ./test.sh: from ctest's labels and its JUnit results.


def labels_of_tests(build_dir):
    """{test name: set of labels}, from ctest's own listing."""
    listing = subprocess.run(["ctest", "--test-dir", build_dir, "--show-only=json-v1"],
                             check=True, capture_output=True, text=True).stdout
    labels = {}
    for test in json.loads(listing).get("tests", []):
        names = set()
        for prop in test.get("properties", []):
            if prop.get("name") == "LABELS":
                names.update(prop.get("value", []))
        labels[test["name"]] = names
    return labels


def results(path):
    """{test name: 'passed' | 'failed' | 'not run'} for the tests of the run."""
    outcome = {}
    for case in ElementTree.parse(path).getroot().iter("testcase"):
        status = case.get("status", "run")
        if case.find("failure") is not None or case.find("error") is not None:
            outcome[case.get("name")] = "failed"
        elif status in ("notrun", "disabled") or case.find("skipped") is not None:
            outcome[case.get("name")] = "not run"
        else:
            outcome[case.get("name")] = "passed"
    return outcome


def print_lab_table(lab, labels, outcome):
    """Prints, for each question of the lab, how many of its tests passed and whether it is
    done; then the tests that need the whole solution, and the others. In the user's language
    (messages.start)."""
    questions = [(q.label, q.title, ", ".join(q.functions)) for q in lab.questions]
    done, part, to_do, not_run = _("done"), _("passed (part run)"), _("TO DO"), _("not run")
    rows = []
    for label, what, where in questions:
        tests = [name for name, names in labels.items() if label in names]
        ran = [name for name in tests if outcome.get(name, "not run") != "not run"]
        passed = [name for name in ran if outcome[name] == "passed"]
        if not ran:
            status = not_run
        elif len(passed) == len(tests):
            status = done
        elif len(passed) == len(ran):
            status = part
        else:
            status = to_do
        rows.append((label.upper(), pgettext("question", what), where,
                     f"{len(passed)}/{len(tests)}", status))
    # The tests that need the whole solution (labels render-solution, gpu-solution, ...).
    whole = [name for name, names in labels.items() if any(n.endswith("-solution") for n in names)]
    whole_ran = [name for name in whole if outcome.get(name, "not run") != "not run"]
    whole_passed = [name for name in whole_ran if outcome[name] == "passed"]
    if whole:
        status = (not_run if not whole_ran else done if len(whole_passed) == len(whole)
                  else part if len(whole_passed) == len(whole_ran) else to_do)
        rows.append((_("all"), _("the whole cloth: pictures, GPU = CPU, model"),
                     _("every question above"), f"{len(whole_passed)}/{len(whole)}", status))
    others = [name for name, names in labels.items()
              if not any(q in names for q, _what, _where in questions) and name not in whole
              and name in outcome and outcome[name] != "not run"]
    other_failed = [name for name in others if outcome[name] == "failed"]

    # TRANSLATORS: the columns of the table of the questions (./test.sh): the question's number,
    # what it asks, where it is answered, how many of its tests pass, its status.
    header = (_("Q"), _("question"), _("where"), _("tests"), _("status"))
    widths = [max(len(row[i]) for row in rows + [header]) for i in range(5)]
    line = "  ".join("{:<%d}" % w for w in widths)
    print()
    print(_("The lab, question by question (./test.sh -L q8 checks one):"))
    print(line.format(*header).rstrip())
    for row in rows:
        print(line.format(*row).rstrip())
    if others:
        failed = ""
        if other_failed:
            failed = _("; failed: %s") % (", ".join(sorted(other_failed)[:5])
                                          + (" ..." if len(other_failed) > 5 else ""))
        print(_("Other tests: %(passed)d of %(count)d passed") % {
            "passed": len(others) - len(other_failed), "count": len(others)} + failed)


# ------------------------------------------------------------------------------------------
# scripts/grade's outputs.

def question_title(lab, q):
    """The question's title in the user's language (grading/lab.json's, through the catalogue)."""
    return pgettext("question", lab.question(q).title)


# What no output may carry as it is: the terminal's colour sequences, then the characters that
# XML 1.0 forbids (C0 controls but tab and newline; lone surrogates, from names that are not
# UTF-8; U+FFFE, U+FFFF), DEL and the C1 controls. A control byte in a compiler's error must not
# make junit.xml unreadable: it is written out as \xNN.
TERMINAL_SEQUENCE = re.compile(r"\x1b\[[0-9;?]*[ -/]*[@-~]")
NOT_TEXT = re.compile("[\x00-\x08\x0b-\x1f\x7f-\x9f\ud800-\udfff\ufffe\uffff]")


def clean_text(text):
    """text as every output can hold it: terminal sequences dropped, a carriage return made a
    line's end, every other control character written out (\x07)."""
    text = TERMINAL_SEQUENCE.sub("", str(text)).replace("\r\n", "\n").replace("\r", "\n")
    return NOT_TEXT.sub(lambda m: f"\\x{ord(m.group()):02x}" if ord(m.group()) < 0x100 else
                        "\ufffd", text)


def clean_record(value):
    """Every text of a record (notes, outputs, messages, names), cleaned in place; returns it."""
    if isinstance(value, dict):
        for key, item in value.items():
            value[key] = clean_record(item)
        return value
    if isinstance(value, list):
        return [clean_record(item) for item in value]
    if isinstance(value, tuple):
        return tuple(clean_record(item) for item in value)
    return clean_text(value) if isinstance(value, str) else value


def headline(message):
    """The line of a failure that says what is wrong in the handout's words ('Q8: ...', in
    French 'Q8 : ...' with a no-break space)."""
    lines = message.splitlines()
    return next((l.strip() for l in lines if re.match(r"^\s*Q\d+[ \u00a0]?:", l)),
                lines[0] if lines else "")


def gradescope_results(record, lab, version, confinement=""):
    points = lab.points
    output = "\n".join(record["notes"]) or _("graded by the teacher's tests of every question")
    if record["build_error"]:
        output += "\n\n" + _("The first compiler error:") + "\n" + record["build_error"]
    return {
        "score": record["score"],
        "execution_time": record["seconds"],
        "output": output,
        # Compiler errors hold <glm::dvec3>: plain text everywhere, never HTML (Gradescope's
        # default for the top-level output).
        "output_format": "text",
        "test_output_format": "text",
        "test_name_format": "text",
        "visibility": "visible",
        "stdout_visibility": "hidden",
        "extra_data": {"max_score": record["max_score"], "version": version,
                       "confinement": confinement,
                       "build_seconds": record.get("build_seconds"),
                       "test_seconds": record.get("test_seconds")},
        "tests": [{"name": f"{q}: {question_title(lab, q)}", "number": q[1:],
                   "score": info["score"], "max_score": points[q],
                   "status": "passed" if info["score"] >= points[q] else "failed",
                   "output": info["output"], "output_format": "text",
                   "visibility": "visible"}
                  for q, info in record["questions"].items()],
    }


def junit_xml(record, lab):
    record = clean_record(json.loads(json.dumps(record)))  # (a copy: valid XML whatever it held)
    points = lab.points
    suites = ElementTree.Element("testsuites", name=f"clothlab {record['name']}")
    total = failed = 0
    for q, info in record["questions"].items():
        suite = ElementTree.SubElement(suites, "testsuite", name=f"{q} {question_title(lab, q)}")
        case = ElementTree.SubElement(suite, "testcase", classname=f"clothlab.{q}",
                                      name=f"{q}: {info['passed']}/{info['tests']} tests, "
                                           f"{info['score']:g}/{points[q]:g} points",
                                      time="0")
        total += 1
        if info["status"] == "build error":
            ElementTree.SubElement(case, "error",
                                   message=_("does not compile")).text = info["output"]
            failed += 1
        elif info["score"] < points[q]:
            ElementTree.SubElement(case, "failure",
                                   message=_("{count} test(s) failed").format(
                                       count=info["tests"] - info["passed"])).text = info["output"]
            failed += 1
        suite.set("tests", "1")
        suite.set("failures", "1" if info["status"] not in ("done", "build error") and
                  info["score"] < points[q] else "0")
        suite.set("errors", "1" if info["status"] == "build error" else "0")
    suites.set("tests", str(total))
    suites.set("failures", str(failed))
    if record["notes"]:
        ElementTree.SubElement(suites, "system-out").text = "\n".join(record["notes"])
    ElementTree.indent(suites)
    return ElementTree.tostring(suites, encoding="unicode", xml_declaration=True) + "\n"


def spreadsheet_text(value):
    """A cell that a spreadsheet reads as text, never as a formula: a value that begins with
    = + - @ (or a tab or carriage return) gets a leading apostrophe."""
    text = str(value)
    return "'" + text if text[:1] in ("=", "+", "-", "@", "\t", "\r") else text


def write_csv(path, records, lab, stopped=None):
    """One row per student; a submission that the grader stopped before has empty scores and
    says why in its notes."""
    questions = list(lab.ids)
    with open(path, "w", newline="") as out:
        writer = csv.writer(out)
        writer.writerow(["student", *questions, "total", "max", "notes"])
        for r in records:
            graded = r.get("graded", True)
            writer.writerow([spreadsheet_text(r["name"]),
                             *(f"{r['questions'][q]['score']:g}" if graded else ""
                               for q in questions),
                             f"{r['score']:g}" if graded else "", f"{r['max_score']:g}",
                             spreadsheet_text(" | ".join(r["notes"]))])


REPORT_STYLE = """
body { font: 14px/1.4 system-ui, sans-serif; margin: 24px; color: #222; }
h1 { font-size: 22px; margin: 0 0 4px; } h2 { font-size: 17px; margin: 24px 0 8px; }
table { border-collapse: collapse; } td, th { border: 1px solid #ccc; padding: 3px 8px; }
th { background: #f0f0f0; } td.num { text-align: right; font-variant-numeric: tabular-nums; }
td.full { background: #c8f0c8; } td.part { background: #fbe7a8; } td.zero { background: #f6c4c4; }
td.err { background: #d9d9d9; } td.notes { font-size: 12px; color: #555; max-width: 520px; }
.bar { display: inline-block; height: 10px; background: #4a8; vertical-align: middle; }
.meta { color: #666; } .stopped { color: #a00; } pre { white-space: pre-wrap; margin: 2px 0; font-size: 12px; }
ol { margin: 4px 0 12px; }
"""


def student_link(name, file):
    """The relative link to a student's own output (--out/students/NAME/FILE)."""
    return "students/" + urllib.parse.quote(name) + "/" + file


def write_report(path, records, lab, version, sandbox, elapsed, stopped=None):
    questions = list(lab.ids)
    points = lab.points
    e = html.escape
    title = e(_("clothlab: grades of the class"))
    out = ["<!DOCTYPE html>", f"<html lang='{e(language())}'><head><meta charset='utf-8'>",
           f"<title>{title}</title>", f"<style>{REPORT_STYLE}</style>", "</head><body>",
           f"<h1>{title}</h1>"]
    if stopped:
        out.append("<p class='stopped'><b>" + e(_("Grading stopped:")) + "</b> " +
                   e(clean_text(stopped)) + "</p>")
    out += ["<p class='meta'>" + e(_("{count} submissions, graded {date} in {seconds:.0f} s; "
                                     "copy version {version}; sandbox: {sandbox}").format(
                count=len(records), date=time.strftime('%Y-%m-%d %H:%M'), seconds=elapsed,
                version=version, sandbox=sandbox)) + "</p>",
            "<h2>" + e(_("The class")) + "</h2>",
            "<table id='class'><tr><th>" + e(_("student")) + "</th>"]
    out += [f"<th title='{e(question_title(lab, q))}'>{q} ({points[q]:g})</th>"
            for q in questions]
    out.append("<th>" + e(_("total")) + f" ({sum(points.values()):g})</th><th>" +
               e(_("notes")) + "</th></tr>")
    for r in records:
        out.append(f"<tr><td>{e(r['name'])}</td>")
        for q in questions:
            info = r["questions"][q]
            if not r.get("graded", True):
                out.append("<td class='num err'>-</td>")
                continue
            kind = ("err" if info["status"] in ("build error", "missing") else
                    "full" if info["score"] >= points[q] else "zero" if info["score"] == 0
                    else "part")
            label = e(_("build")) if info["status"] == "build error" else f"{info['score']:g}"
            tests = e(_("{passed}/{count} tests").format(passed=info["passed"],
                                                           count=info["tests"]))
            out.append(f"<td class='num {kind}' title='{tests}'>{label}</td>")
        total = f"{r['score']:g}" if r.get("graded", True) else "-"
        out.append(f"<td class='num'>{total}</td><td class='notes'>"
                   f"{'<br>'.join(e(n) for n in r['notes'])}</td></tr>")
    out.append("</table>")
    out.append("<p class='meta'>" + e(_(
        "Green: every test passes; yellow: some; red: none; grey: nothing to grade (build: the "
        "question's file does not compile). Points in grading/lab.json.")) + "</p>")
    out += ["<h2>" + e(_("Each question")) + "</h2>",
            "<table id='questions'><tr>" + "".join(
                f"<th>{e(h)}</th>" for h in (_("question"), _("done (all tests pass)"),
                                               _("mean score"), _("tests passed"))) + "</tr>"]
    for q in questions:
        done = sum(1 for r in records if r["questions"][q]["status"] == "done")
        rate = done / len(records) if records else 0
        mean = sum(r["questions"][q]["score"] for r in records) / max(1, len(records))
        passed = sum(r["questions"][q]["passed"] for r in records)
        total = sum(r["questions"][q]["tests"] for r in records)
        out.append(f"<tr><td>{q}: {e(question_title(lab, q))}</td><td class='num'>"
                   f"<span class='bar' style='width:{rate * 120:.0f}px'></span> {done}/"
                   f"{len(records)} ({rate:.0%})</td><td class='num'>{mean:.1f} / "
                   f"{points[q]:g}</td><td class='num'>{passed}/{total}</td></tr>")
    out.append("</table>")
    out.append("<h2>" + e(_("What the class got wrong: the most frequent failures")) + "</h2>")
    for q in questions:
        counts = Counter()
        example = {}
        for r in records:
            seen = set()
            info = r["questions"][q]
            if info["status"] == "build error":
                seen.add((_("does not compile"), _("(each submission's details give its "
                                                   "compiler error)")))
            for test, message, kind in info["failures"]:
                key = (test, headline(message) if message else kind)
                seen.add(key)
                example.setdefault(key, message)
            counts.update(seen)
        if not counts:
            continue
        out.append(f"<h3>{q}: {e(question_title(lab, q))}</h3><ol class='failures'>")
        for (test, first), count in counts.most_common(3):
            more = example.get((test, first), "")
            out.append("<li><b>" + e(_("{count} of {total}").format(count=count,
                                                                   total=len(records))) +
                       f"</b> {e(test)}: <pre>{e(more or first)}</pre></li>")
        out.append("</ol>")
    out.append("<h2>" + e(_("Each submission")) + "</h2>")
    for r in records:
        out.append(f"<details><summary>{e(r['name'])}: {r['score']:g} / {r['max_score']:g}"
                   f"</summary>")
        if r.get("graded", True):
            out.append("<p class='meta'>" + ", ".join(
                f"<a href='{e(student_link(r['name'], f))}'>{f}</a>"
                for f in ("results.json", "junit.xml")) + "</p>")
        if r["notes"]:
            out.append("<pre>" + e("\n".join(r["notes"])) + "</pre>")
        for q, info in r["questions"].items():
            out.append(f"<p><b>{q}</b></p><pre>{e(info['output'])}</pre>")
        out.append("</details>")
    out.append("</body></html>")
    path.write_text("\n".join(out) + "\n")
