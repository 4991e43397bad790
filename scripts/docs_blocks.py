#!/usr/bin/python3
"""Prints the N-th (0-based) fenced code block of LANGUAGE in a Markdown file, as written:
docs_blocks.py FILE LANGUAGE [N]. The install tests run the docs' snippets through it."""
import re
import sys

path, language = sys.argv[1], sys.argv[2]
index = int(sys.argv[3]) if len(sys.argv) > 3 else 0
blocks = re.findall(r"^```" + re.escape(language) + r"\n(.*?)^```", open(path).read(), re.S | re.M)
if index >= len(blocks):
    sys.exit(f"{path}: expected a ```{language} block number {index}, found {len(blocks)} such blocks")
sys.stdout.write(blocks[index])
