"""The typed message definitions written from the schema (their drift: test_generated)."""

from generate import message_types


def test_types_follow_the_schema():
    text = message_types.render()
    assert "class Frame(TypedDict):\n    op: Literal['frame']\n    seq: int\n    time: float\n" in text
    assert "    limited: NotRequired[dict[str, int]]\n" in text
    assert "    id: int | None\n" in text   # an error's id: a request's, or null


def test_javascript_typedefs_follow_the_schema():
    text = message_types.render_js()
    assert " * @typedef {object} Frame\n * @property {'frame'} op\n * @property {number} seq\n" in text
    assert " * @property {Object<string, number>} [limited]\n" in text
    assert " * @property {(number|null)} id\n" in text
    assert 'export const SERVER_OPS = Object.freeze(["hello", ' in text

