"""Reading kcreep's tables: the coefficient table (one row per case), batch
and SLURM chunk tables, and anything else in the same format (comment lines
starting with '#', the last of them naming the columns, then whitespace-
separated rows). Standard library only, so scripts can use it anywhere.
"""


def read(path, numbers=True):
    """Rows of a table as dicts keyed by column name. With numbers, values
    that parse as floats are floats (NaN included), the rest strings."""
    columns, rows = None, []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                columns = line[1:].split()
                continue
            if not line.strip():
                continue
            if columns is None:
                raise ValueError(f"{path}: a row before the column line")
            values = line.split()
            rows.append({c: (_number(v) if numbers else v) for c, v in zip(columns, values)})
    return rows


def read_row(path):
    """The last row of a single-case table (numbers as floats)."""
    rows = read(path)
    if not rows:
        raise ValueError(f"{path}: no rows")
    return rows[-1]


def read_chunk(path):
    """(comment lines, column line, raw rows) of a table, rows without the
    newline: what a gather step needs to merge tables verbatim."""
    comments, rows = [], []
    with open(path) as f:
        for line in f:
            line = line.rstrip("\n")
            if line.startswith("#"):
                if rows:
                    raise ValueError(f"{path}: comment after the column line")
                comments.append(line)
            elif line.strip():
                rows.append(line)
    columns = comments.pop() if comments else None
    return comments, columns, rows


def case_name(path):
    """The table's case column for a namelist path, as kcreep writes it."""
    name = path[path.rfind("/") + 1:]
    dot = name.rfind(".")
    if dot > 0:
        name = name[:dot]
    name = "".join("_" if (c == " " or ord(c) < 33) else c for c in name)
    return name or "-"


def _number(text):
    try:
        return float(text)
    except ValueError:
        return text
