#pragma once
// Graceful stop on SIGINT/SIGTERM: the handler only sets a flag; the step
// loop checks it and ends the run as failed ("interrupted"), so summary.json
// and every CSV row up to the last completed step are written.
namespace cosim {

void install_interrupt_handler();  // call once from main()
bool interrupt_requested();

}  // namespace cosim
