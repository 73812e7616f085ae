// The solver's Web Worker (src/run/worker.rs): the workbench's own module
// instantiated a second time. Its `main` finds no window and serves the
// page's requests; those that come while the module loads are kept here
// (`cdcaEarly`) and handled first.
self.cdcaEarly = [];
self.onmessage = (e) => self.cdcaEarly.push(e.data);
import("./cdca-workbench.js")
    .then((bindings) => bindings.default())
    .catch((e) => {
        // the page's `error` handler says so (WorkerLink)
        setTimeout(() => { throw e; });
    });
