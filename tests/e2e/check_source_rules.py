#!/usr/bin/python3
"""Source rules: the comments and sizes a newcomer relies on. Run by ctest:
  check_source_rules.py <source dir>      checks the tree; prints file:line: rule: detail per violation and
                                           exits 1 when there is one
  check_source_rules.py --self-test <dir>  plants violations (and look-alikes that are fine) in a scratch tree
                                           under <dir> and exits 1 unless exactly the planted ones are caught

The rules:
  comment-date    A comment in engine/, models/ or optimizers/ (.cpp, .hpp, .h, CMakeLists.txt, .cmake) holds
                  a calendar date: an ISO date (2026-11-25, 2026-11), a numeric date (25.11.2026, 11/25/2026), or
                  a month name beside a day or a year ("Nov 2026", "25 November", "November 25, 2026").
                  A year alone is not a date: "Spencer et al. 1997" cites a paper, and "eq. 15" is an equation.
                  Month names count only when capitalised, so "may", "march" and "mar" in prose stay fine.
  comment-cpu     Such a comment names a CPU or a CPU family (Zen 3, EPYC, Xeon, Skylake, Graviton, Apple M1...):
                  measurements on a machine belong in docs/performance.md, the code says why.
  comment-ticket  Such a comment holds an issue, session or pull-request number ("issue 16", "session 12",
                  "PR 7", "#33"): history belongs in the commit messages. Any "#" before a number counts, so
                  a comment numbers other things without it ("lane 3", "step 2").
  outside-doc     A tracked file (code, CMake, Markdown, TOML, scripts) cites a document the repository does not
                  hold (the names in OUTSIDE_DOCS); cite docs/design.md or docs/models.md instead.
  file-size       A .cpp, .hpp or .h in engine/, models/ or optimizers/ has more than 600 lines.
  function-size   A function in engine/, models/, optimizers/ or python/src/ spans more than 80 lines, counted
                  from the line of its opening brace to the line of its closing brace, both included. Functions are found by a brace-matching scanner
                  that drops comments, string and character literals (raw strings too) and preprocessor lines,
                  and classifies each brace by what precedes it: namespace, class/struct/union/enum body,
                  initializer, lambda or function. Lambdas at namespace or class scope count as functions; a
                  lambda inside a function is part of that function. Members defined in a class body count
                  one by one. Exceptions are listed in FUNCTION_EXCEPTIONS, each with its reason.
  include-cycle   Units of one folder of engine/, models/, optimizers/ or datasets/ (a unit: the .hpp and .cpp of
                  one stem) include each other's headers in a loop, so neither can be read, tested or moved
                  without the other; a header of its own for what both need breaks it. Loops not yet broken are
                  listed in INCLUDE_CYCLE_EXCEPTIONS, each with its reason. (Loops across folders are the include
                  layers' check, tests/e2e/check_include_layers.cmake.)
  parse           The scanner could not match the braces of a file (so it could not check it): a failure too.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

MAX_FILE_LINES = 600
MAX_FUNCTION_LINES = 80
COMMENT_DIRS = ("engine", "models", "optimizers")   # comment rules and file sizes
FUNCTION_DIRS = ("engine", "models", "optimizers", "python/src")  # function sizes
CPP_EXTENSIONS = (".cpp", ".hpp", ".h")
# Documents that are not in the repository. Spelled in two parts so that this file does not cite them itself.
OUTSIDE_DOCS = ("DESIGN", "MODELS", "STYLE")
OUTSIDE_DOC_RE = re.compile(r"\b(?:%s)\.md\b" % "|".join(OUTSIDE_DOCS))
# (path, function name) -> reason. Empty: every function in FUNCTION_DIRS keeps to the limit.
FUNCTION_EXCEPTIONS = {}
CYCLE_DIRS = ("engine", "models", "optimizers", "datasets")  # include loops between units of one folder
# The units of a loop (sorted) -> reason.
INCLUDE_CYCLE_EXCEPTIONS = {}  # empty: no loop between the units of a folder
INCLUDE_RE = re.compile(r'^\s*#\s*include\s+"([^"]+)\.(?:hpp|h)"', re.M)

# ---------------------------------------------------------------- comment patterns
_MONTHS = ("January|February|March|April|May|June|July|August|September|October|November|December|"
           "Jan|Feb|Mar|Apr|Jun|Jul|Aug|Sep|Sept|Oct|Nov|Dec")
_MONTH = r"(?:%s)\b\.?" % _MONTHS
_DAY = r"(?:0?[1-9]|[12][0-9]|3[01])(?:st|nd|rd|th)?"
_YEAR = r"(?:19|20)[0-9]{2}"
DATE_PATTERNS = [
    re.compile(r"\b%s-(?:0[1-9]|1[0-2])(?:-(?:0[1-9]|[12][0-9]|3[01]))?\b" % _YEAR),   # 2026-11-25, 2026-11
    re.compile(r"\b%s/(?:0?[1-9]|1[0-2])/(?:0?[1-9]|[12][0-9]|3[01])\b" % _YEAR),       # 2026/11/25
    re.compile(r"\b(?:0?[1-9]|[12][0-9]|3[01])[./](?:0?[1-9]|1[0-2])[./]%s\b" % _YEAR),  # 25.11.2026, 25/11/2026
    re.compile(r"\b(?:0?[1-9]|1[0-2])/(?:0?[1-9]|[12][0-9]|3[01])/%s\b" % _YEAR),       # 11/25/2026
    re.compile(r"\b%s,?\s+(?:%s|%s\b)" % (_MONTH, _YEAR, _DAY)),                          # Nov 2026, Nov 25
    re.compile(r"\b%s\s+(?:of\s+)?%s\b" % (_DAY, _MONTH)),                                # 25 Nov, 25th of November
]
CPU_PATTERN = re.compile(
    r"\b(?:Zen\s?[0-9]?\+?|EPYC|Epyc|Xeon|Ryzen|Threadripper|Opteron|Athlon|Phenom|Bulldozer|Piledriver|"
    r"Pentium|Celeron|Atom|Core\s?(?:i[3579]|Ultra|2\s?Duo)|"
    r"Nehalem|Westmere|Sandy\s?Bridge|Ivy\s?Bridge|Haswell|Broadwell|Skylake|Kaby\s?Lake|Coffee\s?Lake|"
    r"Comet\s?Lake|Cascade\s?Lake|Cooper\s?Lake|Ice\s?Lake|Tiger\s?Lake|Rocket\s?Lake|Alder\s?Lake|"
    r"Raptor\s?Lake|Meteor\s?Lake|Lunar\s?Lake|Arrow\s?Lake|Sapphire\s?Rapids|Emerald\s?Rapids|"
    r"Granite\s?Rapids|Sierra\s?Forest|Knights\s?(?:Landing|Mill)|"
    r"Naples|Milan|Genoa|Bergamo|Turin|Graviton\s?[0-9]?|Neoverse|Ampere\s?Altra|Cortex-[AX][0-9]+|"
    r"Apple\s?M[1-9]|M[1-9]\s?(?:Pro|Max|Ultra)|POWER[89]|POWER1[01]|A64FX|Snapdragon)\b")
TICKET_PATTERN = re.compile(
    r"(?:\b(?:issues?|sessions?|tickets?|PRs?|pull\s+requests?|bugs?|todo)\s*#?\s*[0-9]+\b"
    r"|(?<![\w&#])#[0-9]+\b)", re.IGNORECASE)


def comment_problems(text):
    """The rules a comment's text breaks, as (rule, matched text) pairs."""
    found = []
    for pattern in DATE_PATTERNS:
        for m in pattern.finditer(text):
            found.append(("comment-date", m.group(0)))
    for m in CPU_PATTERN.finditer(text):
        found.append(("comment-cpu", m.group(0)))
    for m in TICKET_PATTERN.finditer(text):
        found.append(("comment-ticket", m.group(0)))
    return found


# ---------------------------------------------------------------- C++ lexer
def lex_cpp(src):
    """Splits C++ source into code and comments. Returns (code, comments): code has the same lines as src with
    comments, string and character literals and preprocessor lines blanked (newlines kept); comments is a list
    of (line, text)."""
    out = []
    comments = []
    i, n, line = 0, len(src), 1
    token = ""                  # the identifier or number being read (R for raw strings, 1'000'000)
    at_line_start = True        # only blanks so far on this line (for preprocessor directives)

    def blank(text):
        return "".join("\n" if c == "\n" else " " for c in text)

    while i < n:
        c = src[i]
        if c == "\n":
            out.append(c)
            line += 1
            i += 1
            token = ""
            at_line_start = True
            continue
        if at_line_start and c == "#":
            j = i
            while j < n and src[j] != "\n":
                if src[j] == "\\" and j + 1 < n and src[j + 1] == "\n":
                    j += 2
                    continue
                if src.startswith("//", j) or src.startswith("/*", j):
                    break
                j += 1
            text = src[i:j]
            out.append(blank(text))
            line += text.count("\n")
            i = j
            at_line_start = False
            continue
        if src.startswith("//", i):
            j = i
            while j < n and src[j] != "\n":
                if src[j] == "\\" and j + 1 < n and src[j + 1] == "\n":
                    j += 2
                    continue
                j += 1
            text = src[i:j]
            comments.append((line, text[2:]))
            out.append(blank(text))
            line += text.count("\n")
            i = j
            token = ""
            continue
        if src.startswith("/*", i):
            j = src.find("*/", i + 2)
            j = n if j < 0 else j + 2
            text = src[i:j]
            for k, part in enumerate(text[2:-2].split("\n")):
                comments.append((line + k, part))
            out.append(blank(text))
            line += text.count("\n")
            i = j
            token = ""
            continue
        if c == "'" and token[:1].isdigit():   # a digit separator
            out.append(c)
            i += 1
            continue
        if c == '"' and token in ("R", "u8R", "uR", "UR", "LR"):
            m = re.match(r'"([^()\\\s]{0,16})\(', src[i:])
            if m:
                end = src.find(")" + m.group(1) + '"', i + len(m.group(0)))
                j = n if end < 0 else end + len(m.group(1)) + 2
                text = src[i:j]
                out.append('"' + blank(text[1:-1]) + '"' if len(text) >= 2 else blank(text))
                line += text.count("\n")
                i = j
                token = ""
                at_line_start = False
                continue
        if c in "\"'":   # a string or character literal, blanked to its quotes
            j = i + 1
            while j < n and src[j] != c and src[j] != "\n":
                j += 2 if src[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(c + " " * (j - i - 2) + c if j - i >= 2 else " ")
            i = j
            token = ""
            at_line_start = False
            continue
        if c.isalnum() or c == "_" or (c == "." and token[:1].isdigit()):
            token += c
        else:
            token = ""
        if not c.isspace():
            at_line_start = False
        out.append(c)
        i += 1
    return "".join(out), comments


def cmake_comments(src):
    """(line, text) of the comments of a CMake file: # to the end of the line outside quoted arguments, and
    bracket comments #[[ ... ]]."""
    comments = []
    i, n, line = 0, len(src), 1
    while i < n:
        c = src[i]
        if c == "\n":
            line += 1
            i += 1
        elif c == '"':
            j = i + 1
            while j < n and src[j] != '"':
                j += 2 if src[j] == "\\" else 1
            line += src[i:j + 1].count("\n")
            i = j + 1
        elif c == "#":
            m = re.match(r"#\[(=*)\[", src[i:])
            if m:
                end = src.find("]" + m.group(1) + "]", i)
                j = n if end < 0 else end + len(m.group(1)) + 2
            else:
                j = src.find("\n", i)
                j = n if j < 0 else j
            text = src[i:j]
            for k, part in enumerate(text.split("\n")):
                comments.append((line + k, part.lstrip("#")))
            line += text.count("\n")
            i = j
        else:
            i += 1
    return comments


# ---------------------------------------------------------------- functions
_CONTROL = {"if", "for", "while", "switch", "catch", "return", "sizeof", "alignof", "decltype", "new", "delete",
            "throw", "co_return", "co_yield", "co_await", "static_assert"}
_SKIP_CALLS = {"noexcept", "throw", "alignas", "__attribute__", "__declspec", "requires"}
_SPECIFIERS = re.compile(r"(?:\s+|\bconst\b|\bvolatile\b|\bnoexcept\b|\boverride\b|\bfinal\b|\bmutable\b|"
                         r"\bconstexpr\b|\bconsteval\b|\btry\b|&&|&|\[\[[^\]]*\]\])$")


def _drop_template_prefix(head):
    """head without a leading template <...> parameter list."""
    m = re.match(r"\s*template\s*<", head)
    if not m:
        return head.strip()
    depth, k = 0, m.end() - 1
    while k < len(head):
        if head[k] == "<":
            depth += 1
        elif head[k] == ">":
            depth -= 1
            if depth == 0:
                break
        k += 1
    return head[k + 1:].strip()


def _collapse(head):
    """head with every balanced (...) group replaced by (); when a '(' is left open (a lambda passed as an
    argument: f(a, [](int x) {), only what follows it, from its last top-level comma on."""
    out, depth = [], 0
    for ch in head:
        if ch == "(":
            if depth == 0:
                out.append(ch)
            depth += 1
        elif ch == ")":
            depth = max(depth - 1, 0)
            if depth == 0:
                out.append(ch)
        elif depth == 0:
            out.append(ch)
    if depth > 0:
        return _collapse(_after_last_top_comma(head[_last_open_paren(head) + 1:]))
    return "".join(out).strip()


def _last_open_paren(head):
    depth = 0
    for k in range(len(head) - 1, -1, -1):
        if head[k] == ")":
            depth += 1
        elif head[k] == "(":
            if depth == 0:
                return k
            depth -= 1
    return -1


def _after_last_top_comma(text):
    depth = 0
    for k in range(len(text) - 1, -1, -1):
        if text[k] in ")]>":
            depth += 1
        elif text[k] in "([<":
            depth = max(depth - 1, 0)
        elif text[k] == "," and depth == 0:
            return text[k + 1:]
    return text


_CONTROL = {"if", "for", "while", "switch", "catch", "return", "sizeof", "alignof", "decltype", "new", "delete",
            "throw", "co_return", "co_yield", "co_await", "static_assert", "typeid", "alignas"}
_SKIP_CALLS = {"noexcept", "throw", "alignas", "__attribute__", "__declspec"}
_SPECIFIERS = re.compile(r"(?:\s+|\bconst\b|\bvolatile\b|\bnoexcept\b|\boverride\b|\bfinal\b|\bmutable\b|"
                         r"\bconstexpr\b|\bconsteval\b|\bstatic\b|\btry\b|&&|&|\[\[[^\]]*\]\])$")
_ENDS_EXPRESSION = ("=", ",", "(", "[", "{", "}", "return", "?", ":", "<", "+", "-", "*", "/", "|", "&&", ">>",
                    "else", "do", "try")


def classify(head):
    """What a '{' at namespace or class scope opens, from the code since the previous statement or body at
    the same depth: 'namespace', 'class', 'function', 'lambda' or 'other' (initializers, blocks)."""
    h = re.sub(r"\[\[[^\]]*\]\]", " ", _drop_template_prefix(head)).strip()    # attributes
    h = re.sub(r"^(?:(?:public|private|protected)\s*:(?!:)\s*)+", "", h)
    if re.match(r"(?:inline\s+)?namespace\b", h) or re.match(r'extern\s*""', h):
        return "namespace"
    h = _collapse(h)
    if re.match(r"(?:(?:typedef|export|static|inline|constexpr|const)\s+)*(?:class|struct|union|enum)\b", h) \
            and "=" not in h and "(" not in h:
        return "class"
    # a trailing requires clause: void f(T x) requires C<T> {
    m = re.search(r"[)\]][^()\]]*?\brequires\b", h)
    if m:
        h = h[:m.end() - len("requires")].rstrip()
    # a trailing return type: cut at the last '->' after the parameter list or a lambda introducer
    arrow = h.rfind("->")
    if arrow > 0 and re.search(r"[)\]]\s*(?:\b(?:const|noexcept|mutable|constexpr|override|final)\b\s*|&&?\s*)*$",
                               h[:arrow]):
        h = h[:arrow].rstrip()
    while True:
        stripped = _SPECIFIERS.sub("", h)
        if stripped.endswith("()"):
            word = re.search(r"([A-Za-z_]\w*)\s*\(\)$", stripped)
            if word and word.group(1) in _SKIP_CALLS:                 # noexcept(...), alignas(...)
                stripped = stripped[:word.start()].rstrip()
        if stripped == h:
            break
        h = stripped
    if not h or (h.endswith(_ENDS_EXPRESSION) and not h.endswith(("::", "operator=", "operator<", "operator-",
                                                                     "operator+", "operator*", "operator/"))):
        # a constructor whose member initializer list ends with a braced one: X::X(int a) : a_{a} {
        if h.endswith("}") and re.search(r"\)\s*(?:noexcept\s*)?:(?!:)", h):
            return "function"
        return "other"
    if h.endswith("]"):
        return "other" if h.endswith("]]") else "lambda"
    if h.endswith(")"):
        before = h[:h.rfind("(")].rstrip() if h.endswith("()") else ""
        if before.endswith("]") or re.search(r"\]\s*<[^\[\]]*>$", before):
            return "lambda"                                              # [](int x) {, []<class T>(T x) {
        word = re.search(r"([A-Za-z_]\w*)$", before)
        if word and word.group(1) in _CONTROL:
            return "other"
        plain = h
        for op in ("operator==", "operator!=", "operator<=", "operator>=", "operator=", "==", "!=", "<=", ">="):
            plain = plain.replace(op, " ")
        if "=" in plain:
            return "other"                                               # int x = f() { is not a function
        return "function"
    return "other"


def functions(code):
    """(name, first line, last line) of each function or lambda in code (as returned by lex_cpp) that is not
    inside another one. Raises ValueError when the braces do not match."""
    found = []
    stack = []               # (kind, line, head, inside_function)
    head = []                # characters since the last statement or body at this depth
    heads = []               # saved heads of the enclosing depths
    line = 1
    for ch in code:
        if ch == "\n":
            line += 1
            head.append(" ")
        elif ch == "{":
            text = "".join(head)
            inside = bool(stack) and (stack[-1][3] or stack[-1][0] in ("function", "lambda"))
            kind = "block" if inside else classify(text)
            stack.append((kind, line, text, inside))
            heads.append(head)
            head = []
        elif ch == "}":
            if not stack:
                raise ValueError("a '}' at line %d closes nothing" % line)
            kind, first, text, inside = stack.pop()
            head = heads.pop()
            if kind in ("function", "lambda") and not inside:
                signature = re.sub(r"^\s*(?:(?:public|private|protected)\s*:(?!:)\s*)+", "", _collapse(text))
                ctor = re.match(r"(.*?\))\s*(?:noexcept\s*(?:\(\))?\s*)?:(?!:)", signature)  # X(int a) : a_(a)
                m = re.search(r"(operator\s*\S+?|[\w:~]+)\s*\(\)[^()]*$", ctor.group(1) if ctor else signature)
                found.append((m.group(1) if m and kind == "function" else kind, first, line))
            if kind in ("other", "block", "lambda"):
                head.append("{}")      # the statement goes on: T x{...}, f([] {...}), a_{a} {
            else:
                head = []
        elif ch == ";":
            head = []
        else:
            head.append(ch)
    if stack:
        raise ValueError("the '{' at line %d is never closed" % stack[-1][1])
    return found


# ---------------------------------------------------------------- the tree
def tracked_files(root):
    """Repository-relative paths: git ls-files when root is a work tree, else every file below root outside
    build folders and hidden folders."""
    try:
        out = subprocess.run(["git", "-C", root, "ls-files", "-z"], capture_output=True, check=True)
        files = [f for f in out.stdout.decode("utf-8", "replace").split("\0") if f]
        if files and os.path.samefile(
                subprocess.run(["git", "-C", root, "rev-parse", "--show-toplevel"], capture_output=True,
                               check=True, text=True).stdout.strip(), root):
            return sorted(f for f in files if os.path.isfile(os.path.join(root, f)))
    except (OSError, subprocess.CalledProcessError):
        pass
    files = []
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames[:] = sorted(d for d in dirnames if not d.startswith((".", "build")))
        for f in filenames:
            files.append(os.path.relpath(os.path.join(dirpath, f), root))
    return sorted(files)


def under(path, dirs):
    return any(path.startswith(d + "/") for d in dirs)


def add_include_edges(edges, path, src):
    """Records in `edges` (unit -> units) the same-folder headers the file at `path` includes, for include_cycles."""
    if not (path.endswith(CPP_EXTENSIONS) and under(path, CYCLE_DIRS)):
        return
    unit, folder = os.path.splitext(path)[0], os.path.dirname(path)
    for included in INCLUDE_RE.findall(src):
        if included != unit and os.path.dirname(included) == folder:
            edges.setdefault(unit, set()).add(included)


def include_cycles(edges):
    """Loops of same-folder includes between units, as lists of unit names (sorted), each loop once."""
    # Tarjan's strongly connected components, iteratively (a folder may hold many units).
    index, low, on_stack, stack, loops, counter = {}, {}, set(), [], [], [0]
    for start in sorted(edges):
        if start in index:
            continue
        work = [(start, iter(sorted(edges.get(start, ()))))]
        index[start] = low[start] = counter[0]
        counter[0] += 1
        stack.append(start)
        on_stack.add(start)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is not None:
                if child not in index:
                    index[child] = low[child] = counter[0]
                    counter[0] += 1
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(sorted(edges.get(child, ())))))
                elif child in on_stack:
                    low[node] = min(low[node], index[child])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                component = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    component.append(member)
                    if member == node:
                        break
                if len(component) > 1:
                    loops.append(sorted(component))
    return sorted(loops)


def check(root):
    """Every violation below root, as 'path:line: rule: detail' strings."""
    problems, edges = [], {}
    for path in tracked_files(root):
        try:
            with open(os.path.join(root, path), encoding="utf-8", errors="replace") as f:
                src = f.read()
        except OSError as e:
            problems.append("%s:0: parse: %s" % (path, e))
            continue
        if "\0" in src:
            continue                                      # binary
        add_include_edges(edges, path, src)
        for number, text in enumerate(src.split("\n"), 1):
            for m in OUTSIDE_DOC_RE.finditer(text):
                problems.append("%s:%d: outside-doc: cites %s, which is not in the repository "
                                "(cite docs/design.md or docs/models.md)" % (path, number, m.group(0)))
        name = os.path.basename(path)
        is_cpp = path.endswith(CPP_EXTENSIONS)
        is_cmake = name == "CMakeLists.txt" or name.endswith(".cmake")
        commented = under(path, COMMENT_DIRS) and (is_cpp or is_cmake)
        if not commented and not (is_cpp and under(path, FUNCTION_DIRS)):
            continue
        code = None
        if is_cpp:
            code, comments = lex_cpp(src)
        else:
            comments = cmake_comments(src)
        for number, text in comments if commented else ():
            for rule, match in comment_problems(text):
                problems.append("%s:%d: %s: '%s' in a comment" % (path, number, rule, match))
        if not is_cpp:
            continue
        lines = src.count("\n") + (0 if src.endswith("\n") or not src else 1)
        if lines > MAX_FILE_LINES and under(path, COMMENT_DIRS):
            problems.append("%s:%d: file-size: %d lines (limit %d)" % (path, lines, lines, MAX_FILE_LINES))
        if under(path, FUNCTION_DIRS):
            try:
                found = functions(code)
            except ValueError as e:
                problems.append("%s:0: parse: %s" % (path, e))
                continue
            for fn, first, last in found:
                length = last - first + 1
                if length > MAX_FUNCTION_LINES and (path, fn) not in FUNCTION_EXCEPTIONS:
                    problems.append("%s:%d: function-size: %s spans %d lines, %d-%d (limit %d)"
                                    % (path, first, fn, length, first, last, MAX_FUNCTION_LINES))
    cycles = ["%s.hpp:0: include-cycle: %s include each other" % (loop[0], ", ".join(loop))
              for loop in include_cycles(edges) if tuple(loop) not in INCLUDE_CYCLE_EXCEPTIONS]
    return cycles + problems


# ---------------------------------------------------------------- self-test
def _body(lines):
    return "".join("  x += %d;\n" % k for k in range(lines))


def self_test(scratch):
    """Plants a tree with known violations and look-alikes; returns the differences between what check()
    finds and what it must find (empty when the check works)."""
    os.makedirs(scratch, exist_ok=True)
    root = tempfile.mkdtemp(prefix="source_rules_", dir=scratch)
    files = {}
    expected = set()

    def plant(path, text, *rules):
        files[path] = text
        for rule in rules:
            expected.add((path, rule))

    # comments: one file per rule and pattern, and look-alikes that must pass
    plant("engine/a/iso_date.cpp", "int a;  // measured 2026-11-25 on the rig\n", ("comment-date", 1))
    plant("engine/a/month_year.hpp", "/* kept since\n   Nov 2026 */\nint b;\n", ("comment-date", 2))
    plant("engine/a/day_month.cpp", "// the 25 November run\n", ("comment-date", 1))
    plant("engine/a/zen.cpp", "int c;\n// faster on Zen 3\n", ("comment-cpu", 2))
    plant("models/epyc.hpp", "// AMD EPYC: 2 cores\n", ("comment-cpu", 1))
    plant("optimizers/xeon.cpp", "/* Sapphire Rapids and Apple M1 */\n", ("comment-cpu", 1))
    plant("engine/a/issue.cpp", "// see issue 16\n", ("comment-ticket", 1))
    plant("engine/a/session.cpp", "// added in session 12\n", ("comment-ticket", 1))
    plant("engine/a/hash.cpp", "int d;  // fixes #33\n", ("comment-ticket", 1))
    plant("engine/CMakeLists.txt", "# Graviton 3 builds need this\nadd_library(x \"#1\")\n", ("comment-cpu", 1))
    plant("engine/a/fine.cpp",
          "// Spencer et al. 1997, eq. 15; the 1997 paper (section 3.2) may use 3 lanes; march on\n"
          "// 3 Markov chains, 12 Decays, Nov. or June alone, version 1.10.3, 2019-2021, lane #a, step 2/3\n"
          "#include <cstdint>\n"
          "const char* s = \"2026-11-25 on Zen 3, issue 16\";  // a string is not a comment\n"
          "const char* r = R\"x(// Zen 3 }{ \")x\";\n"
          "const long big = 1'000'000;  // digit separators are not quotes\n"
          "char q = '}';\n")
    plant("bench/notes.cpp", "// Zen 3, 2026-11-25, issue 16: bench/ is outside the comment rules\n")
    # documents outside the repository, in any tracked file
    plant("docs/guide.md", "See %s.md for the design.\n" % OUTSIDE_DOCS[0], ("outside-doc", 1))
    plant("scripts/run.sh", "#!/bin/sh\n\n# per %s.md\n" % OUTSIDE_DOCS[2], ("outside-doc", 3))
    plant("docs/fine.md", "See docs/design.md and docs/models.md.\n")
    # sizes
    plant("models/long.cpp", "int e;\n" * (MAX_FILE_LINES + 1), ("file-size", MAX_FILE_LINES + 1))
    plant("optimizers/limit.hpp", "int f;\n" * MAX_FILE_LINES)
    long_fn = "int g(int x) {\n" + _body(MAX_FUNCTION_LINES - 2) + "  return x;\n}\n"     # 81 lines
    fine_fn = "int h(int x) {\n" + _body(MAX_FUNCTION_LINES - 3) + "  return x;\n}\n"     # 80 lines
    plant("engine/b/fn.cpp", "namespace n {\nnamespace {\n" + fine_fn + long_fn + "}\n}\n",
          ("function-size", 3 + MAX_FUNCTION_LINES))
    plant("engine/b/members.hpp",
          "template <class T>\nstruct S : Base<T> {\n  S(int a) : a_{a}, b_(a) {\n" + _body(MAX_FUNCTION_LINES - 1)
          + "  }\n  int f() const noexcept {\n    return 1;\n  }\n  int a_{0};\n  int b_;\n};\n",
          ("function-size", 3))
    plant("engine/b/lambda.cpp",
          "const auto k = [](int x) -> int {\n" + _body(MAX_FUNCTION_LINES - 1) + "  return x;\n};\n",
          ("function-size", 1))
    plant("engine/b/nested.cpp",
          "int m(int x) {\n  auto l = [&](int y) {\n    return y;\n  };\n"
          "  const char* s = R\"(}}}})\";\n  // }}}\n  if (x) {\n    x = l(x);\n  }\n  return x;\n}\n"
          "struct T { int v[3] = {1, 2, 3}; };\nenum class E : int { a, b };\n")
    plant("engine/b/requires.hpp",
          "template <class T>\nauto r(T x) -> T requires (sizeof(T) > 1) {\n" + _body(MAX_FUNCTION_LINES - 1)
          + "}\n", ("function-size", 2))
    plant("models/long_fn.cpp", long_fn, ("function-size", 1))
    plant("python/src/long_fn.cpp", long_fn, ("function-size", 1))
    plant("bench/long_fn_outside.cpp", long_fn)
    plant("engine/b/unbalanced.cpp", "int u() {\n  return 0;\n", ("parse", 0))
    # include loops between units of one folder: a.hpp -> b.hpp, b.cpp -> a.hpp; a chain c -> d and an include of
    # another folder's unit are fine
    plant("engine/c/a.hpp", '#include "engine/c/b.hpp"\n', ("include-cycle", 0))
    plant("engine/c/b.hpp", "int b();\n")
    plant("engine/c/b.cpp", '#include "engine/c/b.hpp"\n#include "engine/c/a.hpp"\n')
    plant("engine/c/c.hpp", '#include "engine/c/d.hpp"\n#include "engine/b/fn.hpp"\n')
    plant("engine/c/d.cpp", '#include "engine/c/d.hpp"\n')

    for path, text in files.items():
        full = os.path.join(root, path)
        os.makedirs(os.path.dirname(full), exist_ok=True)
        with open(full, "w") as f:
            f.write(text)
    found = set()
    for problem in check(root):
        path, number, rule = problem.split(":", 3)[:3]
        found.add((path, (rule.strip(), int(number))))
    differences = []
    if found == expected:
        shutil.rmtree(root)                                # kept for a look when the self-test fails
    for path, item in sorted(expected - found):
        differences.append("missed: %s:%d: %s" % (path, item[1], item[0]))
    for path, item in sorted(found - expected):
        differences.append("false alarm: %s:%d: %s" % (path, item[1], item[0]))
    return differences


def main(argv):
    if len(argv) == 3 and argv[1] == "--self-test":
        differences = self_test(argv[2])
        for d in differences:
            print(d)
        print("self-test: %s" % ("failed" if differences else "every planted violation caught, no false alarm"))
        return 1 if differences else 0
    if len(argv) != 2:
        print(__doc__)
        return 2
    problems = check(argv[1])
    for p in problems:
        print(p)
    print("%d violation(s) of the source rules" % len(problems))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
