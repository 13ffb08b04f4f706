// The browser view's page: one HTML document with its style and script inline, served from
// memory (no file from disk, nothing from the network), so it works offline and on any browser.
#include "app/serve/web_server.hpp"

namespace gf::app {
namespace {

// The page talks to the server only through GET /scene.json, GET /state.json, GET /stream.mjpg
// and POST /command (the `live` commands), each with the token it was opened with. Its files are
// app/serve/page/ (page.html, page.css, page.js), put into one document at build time.
#include "web_page.hpp"

}  // namespace

const std::string& webPage() {
  static const std::string page(kPage);
  return page;
}

}  // namespace gf::app
