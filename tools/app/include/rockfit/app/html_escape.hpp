// Text inside the report's HTML and its inline SVG: the five characters that markup gives a meaning to, as
// entities (&amp; &lt; &gt; &quot; &#39;), valid in element content and in quoted attributes of both.
#pragma once

#include <string>

namespace rockfit::app {

std::string EscapeHtml(const std::string& text);

}  // namespace rockfit::app
