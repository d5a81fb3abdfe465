"""The scripts' words in the user's language (docs/translating.md): the catalogues the build
compiles from po/ (build/locale/<lang>/LC_MESSAGES/clothlab.mo), read with Python's gettext, and
the language chosen as the programs choose it (src/core/i18n.cpp): --lang, else LC_ALL,
LC_MESSAGES, LANG, with LANGUAGE first outside the C locale; English where nothing says
otherwise.

    from clothlab_lab.messages import _, ngettext
    messages.start(build_dir)          # once, before the first word
    print(_("Every question's tests pass."))
"""
import gettext
import os
from pathlib import Path

DOMAIN = "clothlab"
_current = gettext.NullTranslations()
_language = "en"


def languages(locale_dir):
    """English, then each language whose catalogue the build compiled."""
    found = sorted(p.name for p in Path(locale_dir).glob("*")
                   if (p / "LC_MESSAGES" / f"{DOMAIN}.mo").is_file() and p.name != "en")
    return ["en"] + found


def language_of_locale(name, known):
    """'fr_FR.UTF-8@euro' -> 'fr' (a catalogue of its language and territory first); English for
    a language without a catalogue."""
    name = name.split(".")[0].split("@")[0].replace("-", "_")
    language, _sep, territory = name.partition("_")
    for code in (f"{language.lower()}_{territory}" if territory else None, language.lower()):
        if code in known:
            return code
    return "en"


def language_from_environment(known, environ=None):
    environ = os.environ if environ is None else environ
    locale = next((environ[v] for v in ("LC_ALL", "LC_MESSAGES", "LANG") if environ.get(v)), "")
    # LANGUAGE lists languages in order of preference; gettext ignores it in the C locale.
    if environ.get("LANGUAGE") and locale not in ("", "C", "POSIX"):
        for entry in environ["LANGUAGE"].split(":"):
            code = language_of_locale(entry, known)
            if entry and (code != "en" or entry.startswith("en")):
                return code
    return language_of_locale(locale, known)


def start(build_dir, language=None):
    """Chooses the language (`language`, else the environment's) among the catalogues of
    build_dir/locale, and reads its catalogue. Returns the language chosen."""
    global _current, _language
    locale_dir = Path(build_dir) / "locale"
    known = languages(locale_dir)
    _language = language if language in known else language_from_environment(known)
    _current = gettext.translation(DOMAIN, localedir=str(locale_dir), languages=[_language],
                                   fallback=True) if _language != "en" else \
        gettext.NullTranslations()
    return _language


def _(text):
    return _current.gettext(text)


def ngettext(singular, plural, n):
    return _current.ngettext(singular, plural, n)


def pgettext(context, text):
    return _current.pgettext(context, text)



def N_(text):
    """Marks a text for the catalogue where it is defined; _() translates it where it is shown."""
    return text


def current_language():
    """The language start() chose ("en" before it)."""
    return _language
