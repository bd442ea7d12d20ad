"""Checks shared by the plugin tests: each check prints ok/FAIL, and the test's exit status is
non-zero when any failed."""

failures = []


def check(condition, message):
    print("%s %s" % ("ok  " if condition else "FAIL", message), flush=True)
    if not condition:
        failures.append(message)
    return condition


def info_value(proxy, info_name):
    """Value of an information-only property, read from the server-side VTK object."""
    proxy.UpdatePropertyInformation()
    prop = proxy.GetProperty(info_name)
    if prop is None or prop.GetNumberOfElements() == 0:
        return None
    return prop.GetElement(0)


def exit_status():
    if failures:
        print("%d check(s) failed" % len(failures))
        return 1
    print("all checks passed")
    return 0
