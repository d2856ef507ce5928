"""What a submission's object file may define (tools/grader/README.md, "Linking").

A submission object is linked into the instructor's executables (the runner,
the chapter program), before the common library and the earlier chapters'
solutions. A symbol it defines could therefore take the place of instructor
code: a strong definition of `rt::run_chapter_program`, `main`, `operator new`
or `rt::write_png` wins over the library's copy, and a weak (COMDAT) copy of an
inline function of common/ (or a template instance) with a different body is
the one the linker keeps whenever the student's object comes first.

The rule, checked on the object's own symbol table before anything links or runs:

  * its exercise's functions may be defined, strong or weak, and stay global:
    the symbols the chapter's runner table (which calls every exercise
    function) or its program (chapter 07's also calls the long double
    instance) references as undefined that the instructor's own compile of the
    chapter's exercise files (the stubs, or in a kit the placeholders) defines;
  * any other strong definition (a function, a variable, an absolute or common
    symbol, an ifunc) is refused, naming the symbol demangled and the rule;
  * any other weak or unique definition (inline functions, template instances,
    vtables and typeinfo, static locals of inline functions: every object
    carries them) is renamed and made local to the object (objcopy; a unique
    symbol stays global under its new name, which no instructor object uses), so the
    student's own calls keep using the student's copy and nothing outside the
    object can bind to it; renaming also renames the COMDAT group it signs, so
    the linker never discards the instructor's copy for the student's either.

The rewritten object is read again and must define nothing global but
exercise functions; otherwise it is refused too.
"""

import hashlib
import os
import shutil
import struct
import subprocess
import tempfile

SHT_SYMTAB = 2
SHT_GROUP = 17
SHN_UNDEF = 0
STB_LOCAL, STB_GLOBAL, STB_WEAK, STB_GNU_UNIQUE = 0, 1, 2, 10
STT_SECTION, STT_FILE = 3, 4
BINDINGS = {STB_GLOBAL: "strong", STB_WEAK: "weak", STB_GNU_UNIQUE: "unique"}


class Unreadable(Exception):
    pass


def _sections(data):
    """The section headers of a 64-bit little-endian ELF relocatable object:
    [(name offset, type, flags, addr, offset, size, link, info, align, entsize)]."""
    if data[:4] != b"\x7fELF" or len(data) < 0x40 or data[4] != 2 or data[5] != 1:
        raise Unreadable("not a 64-bit little-endian ELF file")
    shoff, = struct.unpack_from("<Q", data, 0x28)
    shentsize, shnum, shstrndx = struct.unpack_from("<HHH", data, 0x3A)
    if shoff and shnum == 0:
        shnum = struct.unpack_from("<Q", data, shoff + 0x20)[0]
    if shentsize < 0x40 or shnum > 1 << 20 or shoff + shnum * shentsize > len(data):
        raise Unreadable("its section headers lie outside the file")
    return [struct.unpack_from("<IIQQQQIIQQ", data, shoff + k * shentsize) for k in range(shnum)]


def read_symbols(data):
    """(defined, undefined, signatures): the object's non-local symbols, as {mangled name: binding} and a
    set of names, and the names of the symbols that sign its COMDAT groups (any binding; a group signed
    by a section symbol is refused). Raises Unreadable for a file that is not an ELF object read whole."""
    try:
        sections = _sections(data)
        tables = [k for k, s in enumerate(sections) if s[1] == SHT_SYMTAB]
        if len(tables) > 1:
            raise Unreadable("it has more than one symbol table")
        defined, undefined, signatures = {}, set(), set()
        entries = []
        for index in tables:
            table = sections[index]
            offset, size, link, entsize = table[4], table[5], table[6], table[9]
            if entsize != 24 or offset + size > len(data) or link >= len(sections):
                raise Unreadable("its symbol table is malformed")
            str_off, str_size = sections[link][4], sections[link][5]
            if str_off + str_size > len(data):
                raise Unreadable("its symbol names lie outside the file")
            names = data[str_off:str_off + str_size]
            for k in range(size // 24):
                st_name, st_info, _, st_shndx, _, _ = struct.unpack_from("<IBBHQQ", data, offset + k * 24)
                end = names.find(b"\0", st_name)
                if st_name >= len(names) or end < 0:
                    raise Unreadable("a symbol's name lies outside its string table")
                entries.append((names[st_name:end].decode("latin-1"), st_info >> 4, st_info & 0xF, st_shndx))
        # Old-style COMDAT: the linker keeps the first .gnu.linkonce.* section of a name and matches
        # it against COMDAT groups of the same name, so it could drop an instructor's copy. The
        # compiler never writes them on this platform: refused.
        shstrndx = struct.unpack_from("<H", data, 0x3E)[0]
        if shstrndx < len(sections):
            at, size = sections[shstrndx][4], sections[shstrndx][5]
            section_names = data[at:at + size]
            for s in sections:
                if section_names[s[0]:s[0] + 14] == b".gnu.linkonce.":
                    raise Unreadable("it has a .gnu.linkonce section (an old-style COMDAT the compiler does not make)")
        for s in sections:
            if s[1] == SHT_GROUP:
                if not tables or s[6] != tables[0] or s[7] >= len(entries):
                    raise Unreadable("a COMDAT group names no symbol of its symbol table")
                name, _, kind, _ = entries[s[7]]
                if kind == STT_SECTION or not name:
                    raise Unreadable("a COMDAT group is signed by a section, not by a symbol")
                signatures.add(name)
        for name, bind, kind, shndx in entries[1:]:
            if bind == STB_LOCAL or kind in (STT_SECTION, STT_FILE):
                continue
            if shndx == SHN_UNDEF:
                undefined.add(name)
            elif defined.get(name) != STB_GLOBAL:     # two definitions of one name: the strongest counts
                defined[name] = bind
        return defined, undefined, signatures
    except (IndexError, struct.error) as e:
        raise Unreadable(f"it cannot be read as an ELF object ({e})")


def read_object(path):
    with open(path, "rb") as f:
        return f.read()


_undefined_in = {}     # instructor object -> its undefined symbols (read once per process)


def exercise_symbols(stub_objects, user_objects):
    """The mangled names of a chapter's exercise functions: what the instructor's objects that call
    them (the runner table, the chapter program's) leave undefined and the instructor's compile of
    the exercise files defines."""
    called = set()
    for path in user_objects:
        if path not in _undefined_in:
            _undefined_in[path] = read_symbols(read_object(path))[1]
        called |= _undefined_in[path]
    defined = set()
    for path in stub_objects:
        defined |= set(read_symbols(read_object(path))[0])
    found = called & defined
    if not found:
        raise SystemExit(f"grader: no exercise function found in {user_objects} and {stub_objects}")
    return found


def demangle(names):
    """names demangled by c++filt (the names themselves where it is missing or fails)."""
    names = list(names)
    try:
        result = subprocess.run(["c++filt"], input="\n".join(names) + "\n", capture_output=True, text=True,
                                timeout=20)
        lines = result.stdout.splitlines()
        if result.returncode == 0 and len(lines) == len(names):
            return lines
    except (OSError, subprocess.TimeoutExpired):
        pass
    return names


def _shown(name, demangled):
    text = demangled if demangled == name else f"{demangled} ({name})"
    text = "".join(c if c.isprintable() and c != "\\" else f"\\x{ord(c):02x}" for c in text)
    return text if len(text) <= 300 else text[:300] + "..."


RULE = ("a submission's file may define only its chapter's exercise functions (those its header declares); "
        "give every helper function or variable internal linkage (`static`, or inside `namespace { }`)")


def problem_with(defined, allowed, ex):
    """'' or the refusal's text, when the object defines strong symbols that are not exercise functions."""
    strong = sorted(n for n, bind in defined.items() if bind == STB_GLOBAL and n not in allowed)
    if not strong:
        return ""
    shown = [_shown(n, d) for n, d in zip(strong, demangle(strong))]
    more = f"\n  ... and {len(shown) - 8} more" if len(shown) > 8 else ""
    return (f"{ex} defines {'a symbol' if len(shown) == 1 else str(len(shown)) + ' symbols'} other than "
            f"its exercise's functions:\n  " + "\n  ".join(shown[:8]) + more + f"\nThe rule: {RULE}.")


RENAMED = "rt.submission."


def localised_name(name, ex):
    """The private name a weak copy is renamed to: unique to this exercise file, never a C++ name."""
    tag = hashlib.sha256(f"{ex}\0{name}".encode()).hexdigest()[:16]
    return f"{RENAMED}{tag}.{len(name)}"


def confine(data, allowed, ex, objcopy="objcopy"):
    """Checks a submission object against the rule. Returns (rewritten object bytes, '') or (None, why)."""
    try:
        defined, _, signatures = read_symbols(data)
    except Unreadable as e:
        return None, f"{ex}'s object file: {e}"
    why = problem_with(defined, allowed, ex)
    if why:
        return None, why
    # The weak copies, and every COMDAT group's signature (a group is kept or discarded by its signature's
    # name, and the signature may be a local symbol: ~vector's D5 group signs D1 and D2).
    weak = sorted({n for n in defined if n not in allowed} | {n for n in signatures if n not in allowed})
    if not weak:
        return data, ""
    folder = tempfile.mkdtemp(prefix="rt-confine-")
    try:
        src, dst = os.path.join(folder, "in.o"), os.path.join(folder, "out.o")
        renames, locals_ = os.path.join(folder, "renames"), os.path.join(folder, "locals")
        with open(src, "wb") as f:
            f.write(data)
        with open(renames, "w") as f:
            f.writelines(f"{n} {localised_name(n, ex)}\n" for n in weak)
        with open(locals_, "w") as f:
            f.writelines(f"{localised_name(n, ex)}\n" for n in weak)
        try:
            result = subprocess.run([objcopy, f"--redefine-syms={renames}", f"--localize-symbols={locals_}", src, dst],
                                    capture_output=True, text=True, timeout=60)
        except subprocess.TimeoutExpired:
            return None, f"{ex}'s object file could not be rewritten (objcopy took over 60 s)"
        if result.returncode != 0:
            return None, f"{ex}'s object file could not be rewritten: {result.stderr.strip()[:500]}"
        out = read_object(dst)
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    # The rewritten object must hold no global definition but the exercise's.
    try:
        still, _, signed = read_symbols(out)
    except Unreadable as e:
        return None, f"{ex}'s object file, rewritten: {e}"
    # A unique symbol (a static local of an inline function, `std::to_chars`'s digits) stays global
    # under objcopy --localize-symbol; renamed, no instructor object can name it either.
    renamed_unique = {n for n, bind in still.items() if n.startswith(RENAMED) and bind == STB_GNU_UNIQUE}
    left = sorted({n for n in still if n not in allowed and n not in renamed_unique} |
                  {n for n in signed if n not in allowed and not n.startswith(RENAMED)})
    if left:
        shown = [_shown(n, d) for n, d in zip(left, demangle(left))]
        return None, (f"{ex} defines symbols other than its exercise's functions that could not be made "
                      f"local:\n  " + "\n  ".join(shown[:8]) + f"\nThe rule: {RULE}.")
    return out, ""
