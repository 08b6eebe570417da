"""pytest fixtures for the Python module: a small Sky, and a check that no test left a
Vulkan validation message (every test of the project runs with validation on)."""
import pytest

import skylayers


@pytest.fixture
def small_sky():
    """The built-in scene at 32x18, validation on."""
    sky = skylayers.Sky(validation=True)
    sky.set("output.width", 32)
    sky.set("output.height", 18)
    yield sky
    assert sky.validation_messages == 0, "Vulkan validation messages (printed on stderr)"
