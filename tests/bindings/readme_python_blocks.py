"""Runs the ```python blocks of the repository's README.md and of bindings/python/README.md as
written: per file, in order, in one namespace (later blocks use what earlier ones made), with a
temporary folder as the working directory so whatever a block writes goes there.

Run by ctest (bindings.python_readme_blocks) with the package and library of the build.
"""
import os
import re
import tempfile
import unittest

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
READMES = ("README.md", os.path.join("bindings", "python", "README.md"))

# A fence of three or more backticks opening with the language "python", up to the same fence.
_BLOCK = re.compile(r"^(?P<fence>```+)python[ \t]*\n(?P<code>.*?)^(?P=fence)[ \t]*$", re.MULTILINE | re.DOTALL)


def python_blocks(text):
    """[(first line number of the code, code)] of every ```python block, in order."""
    return [(text.count("\n", 0, m.start("code")) + 1, m.group("code")) for m in _BLOCK.finditer(text)]


def run_blocks(path):
    """Executes the file's blocks in one namespace from a temporary working directory; returns
    how many ran."""
    with open(path, encoding="utf-8") as f:
        blocks = python_blocks(f.read())
    namespace = {"__name__": "__readme__"}
    previous = os.getcwd()
    with tempfile.TemporaryDirectory(prefix="volphys-readme-") as work:
        os.chdir(work)
        try:
            for line, code in blocks:
                # Compiled under the README's name with its line numbers, so a traceback points there.
                exec(compile("\n" * (line - 1) + code, path, "exec"), namespace)
        finally:
            os.chdir(previous)
    return len(blocks)


class Extraction(unittest.TestCase):
    def test_only_python_blocks_with_their_line_numbers(self):
        text = "intro\n```python\na = 1\n```\n```sh\nls\n```\n````python\nb = '```'\n````\n```py\nc\n```\n"
        self.assertEqual(python_blocks(text), [(3, "a = 1\n"), (9, "b = '```'\n")])

    def test_the_python_readme_has_blocks(self):
        with open(os.path.join(REPO, READMES[1]), encoding="utf-8") as f:
            self.assertGreaterEqual(len(python_blocks(f.read())), 3)


class ReadmeBlocksRun(unittest.TestCase):
    def check(self, readme):
        path = os.path.join(REPO, readme)
        count = run_blocks(path)
        if count == 0:
            self.skipTest("%s has no ```python blocks" % readme)
        print("%s: %d python blocks ran" % (readme, count))

    def test_top_level_readme(self):
        self.check(READMES[0])

    def test_python_bindings_readme(self):
        self.check(READMES[1])


if __name__ == "__main__":
    unittest.main()
