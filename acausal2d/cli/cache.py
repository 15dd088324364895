"""``acausal2d cache``: the native cache (compiled C of the models run on
this machine, :mod:`acausal2d.runtime.cstore`): where it lives, what it
holds, its size, and clearing it."""
from ..runtime import cstore


def _mb(n):
    return "%.1f MB" % (n / 1e6) if n >= 1e5 else "%.1f kB" % (n / 1e3)


def cmd_cache(args):
    """``acausal2d cache [path|list|size|verify|clear]``."""
    where = cstore.folder()
    if args.action == "path":
        print(where)
    elif args.action == "list":
        libs, total = cstore.entries()
        for name, size in libs:
            print("%10s  %s" % (_mb(size), name))
        print("%d librar%s, %s in %s" % (len(libs), "y" if len(libs) == 1 else "ies", _mb(total),
                                          where))
        _print_installed()
    elif args.action == "verify":
        checked, damaged = cstore.verify_all()
        print("%d file%s checked against its SHA-256 in %s%s" % (
            checked, "" if checked == 1 else "s", where,
            "; removed as damaged (compiled again when needed): " + ", ".join(damaged)
            if damaged else "; each matches"))
        _print_installed()
    elif args.action == "size":
        libs, total = cstore.entries()
        print("%s (%d librar%s) in %s" % (_mb(total), len(libs), "y" if len(libs) == 1 else "ies",
                                          where))
    else:
        removed, kept = cstore.clear()
        print("removed %d file%s from %s%s" % (removed, "" if removed == 1 else "s", where,
                                               "; kept %d of builds running now" % kept
                                               if kept else ""))
    return 0


def _print_installed():
    """The drivers' objects and the driver on CasADi's C API compiled at
    install (not part of the cache)."""
    from ..runtime.drivers import PREBUILT, installed
    found = installed()
    damaged = [name for name, ok in found if not ok]
    if not found:
        print("no driver objects were compiled at install; they are compiled into the cache "
              "on first use")
    else:
        capi = sum(name.endswith(".so") for name, _ in found)
        check = ("; SHA-256 not matching (reinstall acausal2d): " + ", ".join(damaged)
                 if damaged else "; each matches its SHA-256")
        print("%d driver objects compiled at install in %s (%d of them the driver on CasADi's "
              "C API)%s" % (len(found), PREBUILT, capi, check))


def add_parsers(sub):
    """``acausal2d cache``."""
    c = sub.add_parser("cache", help="the native cache: where it lives (path), its libraries "
                       "(list), its size, verify or clear it")
    c.add_argument("action", nargs="?", default="list",
                   choices=("path", "list", "size", "verify", "clear"),
                   help="path: the folder ($ACAUSAL2D_CACHE_DIR, else ~/.cache/acausal2d/"
                   "cbuild); list (default): the libraries, and the driver objects compiled at "
                   "install; size; verify: check each library's SHA-256 in full (a run checks "
                   "size, time, inode and mode only); clear: remove them (they are "
                   "compiled again when needed)")
    c.set_defaults(func=cmd_cache)
