"""Turning mined specs into a query set: verify, pool, meet the category shares, word.

``collect`` evaluates the miners' proposals and keeps the verified ones per category and
subcategory; ``fit_quotas`` sizes each category to the paper's shares (shrinking the
total when a category cannot be filled); ``select_and_render`` takes candidates round
robin over subcategories and words each with the least-used template that fits.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass

from inherit_sg.ingest.synthetic.query_mining import Miner, SceneFacts, basic_miners
from inherit_sg.ingest.synthetic.query_mining_desc import desc_miners
from inherit_sg.ingest.synthetic.query_templates import (
    RenderContext,
    Template,
    render,
    templates_for,
)
from inherit_sg.ingest.synthetic.query_text import Phrasing
from inherit_sg.ingest.synthetic.scene import ObjectGT
from inherit_sg.ingest.synthetic.truth_spec import ObjectSpec

GROUP_SHARES = {"ABC": 0.404, "D": 0.268, "E": 0.100, "F": 0.228}
ABC_SPLIT = {"A": 0.30, "B": 0.35, "C": 0.35}
CATEGORIES = ("A", "B", "C", "D", "E", "F")
MAX_ANSWERS = 3
MAX_FLOOR_ANSWERS = 8  # "a chair on the second floor" may have more answers
LARGE_FRACTION = 0.15  # of category A, at most this share with more than MAX_ANSWERS
_ATTEMPTS_PER_SLOT = 40
_LOOKAHEAD = 12  # candidates considered at once when balancing target kinds


@dataclass
class Candidate:
    """A verified request before and after wording."""

    category: str
    subcategory: str
    spec: ObjectSpec
    answer: list[ObjectGT]
    excluded: int = 0
    text: str = ""
    template: str = ""


def all_miners() -> dict[str, dict[str, Miner]]:
    """Category → subcategory → miner."""
    merged = basic_miners() | desc_miners()
    return {c: merged[c] for c in CATEGORIES}


def _verify(facts: SceneFacts, cat: str, sub: str, spec: ObjectSpec) -> Candidate | None:
    answer = facts.index.match(spec)
    limit = MAX_FLOOR_ANSWERS if (cat, sub) == ("A", "floor") else MAX_ANSWERS
    if not 1 <= len(answer) <= limit:
        return None
    excluded = 0
    if cat == "D":
        if spec.negation_count() != 1:
            return None
        excluded = len(facts.index.match(spec.positive())) - len(answer)
        if excluded <= 0:
            return None
    return Candidate(cat, sub, spec, list(answer), excluded)


def collect(facts: SceneFacts, quotas: dict[str, int]) -> dict[str, dict[str, list[Candidate]]]:
    """Verified candidates per category and subcategory, up to each category's quota."""
    seen: set[str] = set()
    pools: dict[str, dict[str, list[Candidate]]] = {}
    abc = quotas["A"] + quotas["B"] + quotas["C"]
    for cat, miners in all_miners().items():
        # A-C share one quota: any of the three may have to cover for another.
        cap = max(1, math.ceil(0.6 * abc) if cat in "ABC" else quotas[cat])
        pools[cat] = {}
        for sub, miner in miners.items():
            pool: list[Candidate] = []
            for attempt, spec in enumerate(miner(facts)):
                if len(pool) >= cap or attempt > cap * _ATTEMPTS_PER_SLOT + 100:
                    break
                key = spec.key()
                if key in seen:
                    continue
                cand = _verify(facts, cat, sub, spec)
                if cand is not None:
                    seen.add(key)
                    pool.append(cand)
            pools[cat][sub] = pool
    return pools


def _largest_remainder(total: int, shares: dict[str, float]) -> dict[str, int]:
    raw = {k: total * s / sum(shares.values()) for k, s in shares.items()}
    out = {k: math.floor(v) for k, v in raw.items()}
    rest = sorted(raw, key=lambda k: raw[k] - out[k], reverse=True)
    for k in rest[: total - sum(out.values())]:
        out[k] += 1
    return out


def fit_quotas(wanted: int, pools: dict[str, dict[str, list[Candidate]]] | None) -> dict[str, int]:
    """Queries per category for ``wanted`` in total, at the paper's shares.

    With ``pools``, the total shrinks until every category group can be filled, and A–C
    is split by ``ABC_SPLIT`` with any shortfall of one moved to the others.
    """
    sizes = {c: sum(len(p) for p in pools[c].values()) for c in CATEGORIES} if pools else None
    total = wanted
    if sizes is not None:
        groups = {"ABC": sizes["A"] + sizes["B"] + sizes["C"], **{c: sizes[c] for c in "DEF"}}
        total = min(wanted, *(math.floor(groups[g] / s) for g, s in GROUP_SHARES.items()))
    per_group = _largest_remainder(total, GROUP_SHARES)
    quotas = _largest_remainder(per_group["ABC"], ABC_SPLIT)
    if sizes is not None:
        for _ in range(3):
            spare = sum(max(0, quotas[c] - sizes[c]) for c in "ABC")
            quotas = {c: min(quotas[c], sizes[c]) for c in "ABC"}
            for c in "ABC":
                room = sizes[c] - quotas[c]
                quotas[c] += min(room, spare)
                spare -= min(room, spare)
    quotas.update({c: per_group[c] for c in "DEF"})
    return quotas


def _word(
    cand: Candidate,
    templates: list[Template],
    usage: dict[str, int],
    texts: set[str],
    rng: random.Random,
) -> bool:
    phrasing = Phrasing(cand.spec, rng.randrange(1 << 30))
    ctx = RenderContext(cand.category, cand.spec, len(cand.answer), cand.excluded, phrasing)
    ties = {t.id: rng.random() for t in templates}
    for template in sorted(templates, key=lambda t: (usage[t.id], ties[t.id])):
        text = render(template, ctx)
        if text is None or text.lower() in texts:
            continue
        texts.add(text.lower())
        usage[template.id] += 1
        cand.text, cand.template = text, template.id
        return True
    return False


def _subject(cand: Candidate) -> str:
    return cand.spec.function or ",".join(cand.spec.labels)


def _pop_least_used(queue: list[Candidate], subjects: dict[str, int]) -> Candidate:
    """The candidate among the next few whose target kind was asked about least so far."""
    window = range(min(len(queue), _LOOKAHEAD))
    best = min(window, key=lambda i: subjects.get(_subject(queue[i]), 0))
    return queue.pop(best)


def select_and_render(
    pools: dict[str, dict[str, list[Candidate]]], quotas: dict[str, int], rng: random.Random
) -> list[Candidate]:
    """Pick each category's quota round robin over its subcategories and word each pick."""
    texts: set[str] = set()
    chosen: list[Candidate] = []
    for cat in CATEGORIES:
        templates = templates_for(cat)
        usage = {t.id: 0 for t in templates}
        queues = [list(p) for p in pools[cat].values() if p]
        rng.shuffle(queues)
        large_left = int(LARGE_FRACTION * quotas[cat])
        picked = 0
        subjects: dict[str, int] = {}
        while picked < quotas[cat] and any(queues):
            for queue in queues:
                while queue and picked < quotas[cat]:
                    cand = _pop_least_used(queue, subjects)
                    large = len(cand.answer) > MAX_ANSWERS
                    if large and large_left <= 0:
                        continue
                    if _word(cand, templates, usage, texts, rng):
                        subjects[_subject(cand)] = subjects.get(_subject(cand), 0) + 1
                        large_left -= int(large)
                        chosen.append(cand)
                        picked += 1
                        break
    return chosen
