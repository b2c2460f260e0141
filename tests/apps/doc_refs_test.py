"""Every place the commands and the Python module send a reader is there: each docs/FILE.md or
README.md named in a --help text, a usage error or a docstring exists, and a section named after it
("docs/scenes.md ('rbsim scenes')") is a heading of that file.

Usage: doc_refs_test.py MASSPROPS RBSIM SOURCE_DIR PYTHONPATH
"""
import os
import re
import subprocess
import sys

massprops, rbsim, source, pythonpath = sys.argv[1:5]

texts = {}
for name, argv in {
    "massprops --help": [massprops, "--help"],
    "massprops batch --help": [massprops, "batch", "--help"],
    "massprops merge --help": [massprops, "merge", "--help"],
    "massprops fill --help": [massprops, "fill", "--help"],
    "massprops validate --help": [massprops, "validate", "--help"],
    "rbsim --help": [rbsim, "--help"],
    "rbsim poses --help": [rbsim, "poses", "--help"],
    "rbsim (no arguments)": [rbsim],
    "massprops (no arguments)": [massprops],
}.items():
    run = subprocess.run(argv, capture_output=True, text=True)
    texts[name] = run.stdout + run.stderr
env = dict(os.environ, PYTHONPATH=pythonpath)
pydoc = subprocess.run(["/usr/bin/python3", "-m", "pydoc", "massprops", "massprops.dynamics"], capture_output=True,
                       text=True, env=env)
assert pydoc.returncode == 0, pydoc.stderr
texts["pydoc massprops"] = pydoc.stdout

REF = re.compile(r"(README(?:\.md)?|docs/[\w.-]+\.md)(?: \('([^']+)'\))?")


def headings(path):
    with open(path, encoding="utf-8") as f:
        return [line.lstrip("#").strip() for line in f if line.startswith("#")]


failures, checked = [], 0
for where, text in texts.items():
    text = re.sub(r"\s+", " ", text)  # help texts are wrapped
    for m in REF.finditer(text):
        doc, section = m.group(1), m.group(2)
        checked += 1
        if doc == "README":
            failures.append(f"{where}: 'README' without a file and section a reader can find: ...{m.group(0)}...")
            continue
        path = os.path.join(source, doc)
        if not os.path.isfile(path):
            failures.append(f"{where}: {doc} does not exist")
        elif section and not any(section in h for h in headings(path)):
            failures.append(f"{where}: {doc} has no heading '{section}'")
for f in failures:
    print("FAIL:", f)
print(f"{checked} references checked, {len(failures)} wrong")
assert checked >= 5, "the help texts name fewer places than they did: is the pattern still right?"
sys.exit(1 if failures else 0)
