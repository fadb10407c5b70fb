"""Reading CONTACT's input files (.inp) where kcreep's scripts and tests need
their numbers directly. Standard library only."""


def gap_values(path, count):
    """The first `count` values (as text) of the undeformed distance of the
    first case: the numbers after its IBASE line (IBASE = 9: h for all
    elements, x fastest), up to the MODULE line of the next case."""
    with open(path) as f:
        lines = f.read().split("\n")
    start = next(i for i, l in enumerate(lines) if "IBASE" in l and not l.startswith("%")) + 1
    values = []
    for line in lines[start:]:
        if "MODULE" in line:
            break
        values += line.split()
    return values[:count]
